/** drop_object_after_unseen_steps = N (issue 29, item 2), to the step, in the dynamic EKF with
 * the paper's object model, cv and mm: an object without readings for N steps leaves the
 * state at the end of that step (N - 1 steps: it stays), its track (poses, with cv and mm the
 * velocity) and f_0 are recorded exactly as they were in the state (record_dropped) or
 * forgotten, its later readings are skipped and counted; dropping is a marginalization, so the
 * ego estimate equals the run without it until the object's readings come back. With
 * feature_labels = classify (ObjectDropClassify.*) a dropped object's returning tracks restart
 * as a new object. */
#include <dynslam/common/model_options.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam_test/option_errors.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <set>

#include "any_backend.h"

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const std::string kIni = script::kFilterKeys +
                         "Sigma_0 = [1e-6 1e-6 1e-8]\n"
                         "Sigma_xi = [1e-2 1e-2]\n"
                         "[ObjectModel]\ncv_dt = 0.5\n"
                         "[DynamicKFSLAM]\n";  // the tests' keys follow
constexpr int kSteps = 10, kUnseen = 3;
/** Object 0 is read at steps 0..3 and 8..9 (unseen 4..7: dropped at the end of step 6);
 * object 1 at 0..3 and 6..9 (unseen 4..5: N - 1 steps, kept). */
bool seen(int obj, int k) { return k <= 3 || k >= (obj == 0 ? 8 : 6); }
/** An object's three features about its centre. */
const Eigen::Vector2d off[3] = {{1.2, 0}, {-0.6, 0.9}, {-0.6, -0.9}};

script::TSeen objectsAt(int k)
{
	script::TSeen s;
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

/** Steps 0..steps-1 of the scripted drive: four static landmarks and objects(k) at step k. */
std::vector<TStep> run(CDynamicKFSLAM2D& f, const std::function<void(int)>& atStep = {},
                       int steps = kSteps,
                       const std::function<script::TSeen(int)>& objects = objectsAt)
{
	const script::TSeen statics{{0, {6, 6}}, {1, {-6, 6}}, {2, {-6, -6}}, {3, {6, -6}}};
	const Eigen::Vector3d u(0.5, 0.0, 0.05);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	std::vector<TStep> out;
	for (int k = 0; k < steps; ++k)
	{
		if (k > 0) x = models::composePose(x, u);
		script::TSeen s = statics;
		for (const auto& r : objects(k)) s.push_back(r);
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

namespace
{
/** feature_labels = classify (issue 29): one car of anonymous tracks 100-102 at 1 m per step,
 * read at steps 0..3 and 9..13 (unseen 4..8); with N = 3 it is dropped while unseen, and when
 * its tracks are read again they restart as new candidates under fresh IDs
 * (TRoutedStep::restarted) and form a new object once decided moving: none of their readings
 * reaches the dropped object. Without the drop they are the old object's readings (time t). */
constexpr int kClassifySteps = 14;
script::TSeen carAt(int k)
{
	script::TSeen s;
	if (k > 3 && k < 9) return s;
	const Eigen::Vector2d car(2 + 1.0 * k, 5);
	for (int i = 0; i < 3; ++i) s.push_back({100 + i, car + off[i]});
	return s;
}

struct TClassifyStep
{
	TStepReport report;
	estimator::TRoutedStep routed;
};

std::vector<TClassifyStep> runClassify(const std::string& extra)
{
	auto f = filter("feature_labels = classify\n" + extra);
	std::vector<TClassifyStep> out;
	run(
	    *f,
	    [&](int) {
		    out.push_back({f->getLastStepReport(), f->lastRoutedStep()});
	    },
	    kClassifySteps, carAt);
	return out;
}

/** The objects the step's readings went to. */
std::set<int32_t> objectsRead(const estimator::TRoutedStep& r)
{
	std::set<int32_t> o;
	for (const auto& m : r.readings)
		if (m.object >= 0) o.insert(m.object);
	return o;
}
}  // namespace

TEST(ObjectDropClassify, DroppedObjectsTracksRestartAsANewObject)
{
	const std::vector<TClassifyStep> with = runClassify("drop_object_after_unseen_steps = 3\n");
	const std::vector<TClassifyStep> without = runClassify("");
	// The car is decided moving within its first four sightings in both runs: one object.
	const std::set<int32_t> before = objectsRead(with[3].routed);
	ASSERT_EQ(before.size(), 1u);
	ASSERT_EQ(objectsRead(without[3].routed), before);
	const int32_t car = *before.begin();
	size_t dropped = 0;
	for (int k = 0; k < kClassifySteps; ++k) dropped += with[size_t(k)].report.dropped_objects;
	EXPECT_EQ(dropped, 1u);
	// Step 9: the three tracks are read again. With the drop they restart (fresh candidates, no
	// reading for the dropped object, none skipped as a dropped object's); without it they are
	// the old object's readings.
	EXPECT_EQ(with[9].routed.restarted, 3u);
	EXPECT_EQ(with[9].report.skipped_dropped_object, 0u);
	EXPECT_EQ(without[9].routed.restarted, 0u);
	EXPECT_EQ(objectsRead(without[9].routed), before);
	std::set<int32_t> after;
	for (int k = 9; k < kClassifySteps; ++k)
	{
		EXPECT_EQ(objectsRead(with[size_t(k)].routed).count(car), 0u) << "step " << k;
		for (const int32_t o : objectsRead(with[size_t(k)].routed)) after.insert(o);
	}
	// Decided moving again: one new object, not the dropped one.
	ASSERT_EQ(after.size(), 1u);
	EXPECT_NE(*after.begin(), car);
}

TEST(ObjectDropClassify, BoxesAreRejectedClassifyAccepted)
{
	const std::string head = "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1 1]\n";
	{
		mrpt::config::CConfigFileMemory c(
		    head + "drop_object_after_unseen_steps = 3\nfeature_labels = classify\n");
		TModelOptions o;
		EXPECT_NO_THROW(o.loadFromConfigFile(c, "DynamicKFSLAM"));
	}
	dynslam_test::expectOptionsError(
	    head + "drop_object_after_unseen_steps = 3\nfeature_labels = boxes\n",
	    {"drop_object_after_unseen_steps", "ids and classify"});
}
