/** drop_object_after_unseen_steps = N (issue 29, item 2), to the step, in the dynamic EKF with
 * the paper's object model, cv and mm: an object without readings for N steps leaves the
 * state at the end of that step (N - 1 steps: it stays), its track (poses, with cv and mm the
 * velocity) and f_0 are recorded exactly as they were in the state (record_dropped) or
 * forgotten, its later readings are skipped and counted; dropping is a marginalization, so the
 * ego estimate equals the run without it until the object's readings come back. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/landmark_ids.h>
#include <dynslam/model_options.h>
#include <dynslam_test/option_errors.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>

#include <set>

#include "any_backend.h"

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const std::string kIni =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-4 1e-4]\n"
    "motion_noise = action\n"
    "Sigma_0 = [1e-6 1e-6 1e-8]\n"
    "Sigma_xi = [1e-2 1e-2]\n"
    "[ObjectModel]\ncv_dt = 0.5\n"
    "[DynamicKFSLAM]\n";  // the tests' keys follow
constexpr int kSteps = 10, kUnseen = 3;
/** Object 0 is read at steps 0..3 and 8..9 (unseen 4..7: dropped at the end of step 6);
 * object 1 at 0..3 and 6..9 (unseen 4..5: N - 1 steps, kept). */
bool seen(int obj, int k) { return k <= 3 || k >= (obj == 0 ? 8 : 6); }

script::TSeen objectsAt(int k)
{
	script::TSeen s;
	const Eigen::Vector2d off[3] = {{1.2, 0}, {-0.6, 0.9}, {-0.6, -0.9}};
	for (int obj = 0; obj < 2; ++obj)
	{
		if (!seen(obj, k)) continue;
		const Eigen::Vector2d c = obj == 0 ? Eigen::Vector2d(2 + 0.4 * k, 5)
		                                   : Eigen::Vector2d(-3 + 0.3 * k, -4 + 0.1 * k);
		for (int f = 0; f < 3; ++f) s.push_back({ids::objectFeatureId(obj, f), c + off[f]});
	}
	return s;
}

struct TStep
{
	Eigen::Vector3d ego;
	TStepReport report;
	size_t live = 0;
};

std::vector<TStep> run(CDynamicKFSLAM2D& f, const std::function<void(int)>& atStep = {})
{
	const script::TSeen statics{{0, {6, 6}}, {1, {-6, 6}}, {2, {-6, -6}}, {3, {6, -6}}};
	const Eigen::Vector3d u(0.5, 0.0, 0.05);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	std::vector<TStep> out;
	for (int k = 0; k < kSteps; ++k)
	{
		if (k > 0) x = models::composePose(x, u);
		script::TSeen s = statics;
		for (const auto& r : objectsAt(k)) s.push_back(r);
		f.processActionObservation(script::action(k == 0 ? Eigen::Vector3d::Zero() : u,
		                                          k == 0 ? Eigen::Matrix3d::Zero() : U),
		                           script::frame(x, s));
		const auto p = f.getEgoPose().mean;
		out.push_back(
		    {Eigen::Vector3d(p.x(), p.y(), p.phi()), f.getLastStepReport(), f.liveObjectCount()});
		if (atStep) atStep(k);
	}
	return out;
}

std::unique_ptr<CDynamicKFSLAM2D> filter(const std::string& extra)
{
	auto f = std::make_unique<CDynamicKFSLAM2D>();
	f->setMinLoggingLevel(mrpt::system::LVL_ERROR);
	mrpt::config::CConfigFileMemory c(kIni + extra);
	f->loadOptions(c);
	return f;
}
}  // namespace

TEST(ObjectDrop, UnseenForNStepsDroppedRecordedAndSkippedNMinusOneKept)
{
	for (const std::string model : {"paper", "cv", "mm"})
		for (const bool recorded : {true, false})
		{
			SCOPED_TRACE(model + (recorded ? " recorded" : " forgotten"));
			const std::string keys = "object_model = " + model + "\n";
			// The run without the drop, its object 0 at the end of step 6 (when the other run
			// drops it; both are the same computation up to there).
			auto ref = filter(keys);
			std::vector<TObjectFeatureEstimate> f0Before;
			TObjectTrack trackBefore;
			const std::vector<TStep> without = run(*ref,
			                                       [&](int k)
			                                       {
				                                       if (k != 6) return;
				                                       f0Before = ref->getObjectFeatures();
				                                       trackBefore = ref->getObjectTracks().at(0);
			                                       });
			auto f = filter(keys + "drop_object_after_unseen_steps = " + std::to_string(kUnseen) +
			                "\n" + (recorded ? "" : "record_dropped = false\n"));
			const std::vector<TStep> with = run(*f);
			for (int k = 0; k < kSteps; ++k)
			{
				const TStepReport& r = with[size_t(k)].report;
				EXPECT_EQ(r.dropped_objects, k == 6 ? 1u : 0u) << "step " << k;
				EXPECT_EQ(with[size_t(k)].live, k < 6 ? 2u : 1u) << "step " << k;
				EXPECT_EQ(r.skipped_dropped_object, k >= 8 ? 3u : 0u) << "step " << k;
				EXPECT_EQ(without[size_t(k)].report.dropped_objects, 0u);
				// A marginalization: the same ego until object 0's readings come back (with cv
				// they update the ego in the run without the drop).
				if (k < 8 || model == "paper")
				{
					EXPECT_LT((with[size_t(k)].ego - without[size_t(k)].ego).norm(), 1e-12)
					    << "step " << k;
				}
			}
			for (const auto& b : f->getLayout().blocks()) EXPECT_NE(b.object, 0) << "in the state";
			EXPECT_FALSE(f->getObjectWorldPose(0).has_value());
			EXPECT_TRUE(f->getObjectWorldPose(1).has_value());
			const TObjectTrack track = f->getObjectTracks().at(0);
			std::vector<TObjectFeatureEstimate> f0After;
			for (const auto& e : f->getObjectFeatures())
				if (e.object == 0) f0After.push_back(e);
			if (!recorded)
			{
				EXPECT_TRUE(track.poses.empty());
				EXPECT_TRUE(f0After.empty());
				continue;
			}
			// Recorded exactly as they were in the state when dropped.
			ASSERT_EQ(f0After.size(), 3u);
			size_t matched = 0;
			for (const auto& a : f0After)
				for (const auto& b : f0Before)
					if (b.object == 0 && b.id == a.id && b.at_time0)
					{
						EXPECT_EQ(a.mean, b.mean);
						EXPECT_EQ(a.cov, b.cov);
						++matched;
					}
			EXPECT_EQ(matched, 3u);
			ASSERT_EQ(track.poses.size(), trackBefore.poses.size());
			for (const auto& p : track.poses) EXPECT_FALSE(p.in_state);
			const TObjectPoseEstimate &a = track.poses.back(), &b = trackBefore.poses.back();
			EXPECT_TRUE(b.in_state);
			EXPECT_EQ(a.step, model == "paper" ? 3 : 6);  // cv, mm: predicted up to the drop
			EXPECT_EQ(a.step, b.step);
			EXPECT_EQ(a.mean, b.mean);
			EXPECT_EQ(a.cov, b.cov);
			EXPECT_EQ(a.velocity.size(), model == "paper" ? 0 : 3);
			EXPECT_EQ(a.velocity, b.velocity);
			EXPECT_EQ(a.velocity_cov, b.velocity_cov);
			EXPECT_EQ(a.mode_probabilities.size(), model == "mm" ? 4 : 0);
			EXPECT_EQ(a.mode_probabilities, b.mode_probabilities);
		}
}

TEST(ObjectDrop, BadInputIsAClearError)
{
	const std::string head = "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1 1]\n";
	for (const auto& [keys, word] : std::vector<std::pair<std::string, std::string>>{
	         {"drop_object_after_unseen_steps = -1\n", ">= 0"},
	         {"drop_object_after_unseen_steps = 3\nfeature_labels = boxes\n", "ids and classify"}})
		dynslam_test::expectOptionsError(head + keys, {"drop_object_after_unseen_steps", word});
	// The framework's back-ends do not implement it.
	const std::string ini = kIni + "drop_object_after_unseen_steps = 3\n[Framework]\n";
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		if (kind == "ekf") continue;
		EXPECT_THROW(dynslam_test::anyBackend(kind, ini), std::invalid_argument) << kind;
	}
}
