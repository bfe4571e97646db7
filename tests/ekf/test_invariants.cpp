/** After every step: covariance symmetric and PSD, pads unit-variance and uncorrelated, slot
 * table in step with the state; object poses and drop policies as configured. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "tiny_scenario.h"

using namespace dynslam;

namespace
{
/** Returns the number of pads. The pads are checked against an independent count from the
 * slot table: the second entry of every ObjectPoseB slot (3-dof object poses), nothing else. */
size_t checkInvariants(const CDynamicKFSLAM2D& f, size_t step)
{
	std::vector<size_t> expectedPads;
	const auto& slots = f.getSlots();
	for (size_t i = 0; i < slots.size(); ++i)
		if (slots[i].kind == SlotKind::ObjectPoseB) expectedPads.push_back(3 + 2 * i + 1);
	std::vector<size_t> pads = f.padIndices();
	std::sort(pads.begin(), pads.end());
	EXPECT_EQ(pads, expectedPads) << "step " << step;
	const Eigen::MatrixXd P = f.fullCov().asEigen();
	EXPECT_EQ(size_t(P.rows()), 3 + 2 * f.getSlots().size()) << "step " << step;
	if (size_t(P.rows()) != 3 + 2 * f.getSlots().size()) return 0;
	const double scale = std::max(1.0, P.cwiseAbs().maxCoeff());
	EXPECT_LE((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale) << "step " << step;
	const double lmin = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (P + P.transpose()))
	                        .eigenvalues()
	                        .minCoeff();
	EXPECT_GE(lmin, -1e-10 * scale) << "step " << step;
	for (const size_t i : pads)
	{
		EXPECT_EQ(P(i, i), 1.0) << "pad variance, step " << step;
		EXPECT_EQ(f.fullMean()[i], 0.0);
		Eigen::VectorXd row = P.row(Eigen::Index(i)).transpose();
		row[Eigen::Index(i)] = 0;
		EXPECT_EQ(row.cwiseAbs().maxCoeff(), 0.0) << "pad correlated, step " << step;
	}
	return pads.size();
}
}  // namespace

TEST(DynamicInvariants, CovarianceSymmetricPsdAndPadsClean)
{
	for (bool sparse : {true, false})
		for (bool smoothing : {false, true})
			for (bool dropT : {true, false})
			{
				dynslam_test::TinyScenarioOptions o;
				o.objects = 3;
				o.features_per_object = 3;
				o.cartesian_noise = true;
				o.steps = 35;
				const auto sc = dynslam_test::makeTinyScenario(o);
				CDynamicKFSLAM2D f;
				f.options.measurement_model = models::MeasurementModel::Cartesian;
				f.options.Sigma_v = o.Sigma_v;
				f.options.Sigma_0 = o.Sigma_w;
				f.options.smoothing = smoothing;
				f.options.keep_last_poses = smoothing ? 3 : 1;
				f.options.drop_time_t_features = dropT;
				f.options.sparse_static_update = sparse;
				f.reset();
				size_t poses = 0, smooth = 0, padsSeen = 0;
				for (size_t k = 0; k < sc.actions.size(); ++k)
				{
					f.processActionObservation(sc.actions[k], sc.frames[k]);
					padsSeen += checkInvariants(f, k);
					poses += f.getLastStepReport().object_poses_added;
					smooth += f.getLastStepReport().smoothing_updates;
					// At most K poses per object stay in the state.
					std::map<int32_t, int> inState;
					for (const auto& s : f.getSlots())
						if (s.kind == SlotKind::ObjectPoseA) ++inState[s.object];
					for (const auto& [obj, n] : inState) EXPECT_LE(n, f.options.keep_last_poses);
					if (dropT)
					{
						for (const auto& s : f.getSlots())
							EXPECT_NE(s.kind, SlotKind::ObjectFeatureT);
					}
				}
				EXPECT_GT(poses, 20u);
				EXPECT_GT(padsSeen, 20u);  // 3-feature objects: 3-dof poses, one pad each
				if (smoothing)
				{
					EXPECT_GT(smooth, 10u);
				}
				// Every object's history: one pose per step it was seen after its first sighting.
				for (const auto& [obj, tr] : f.getObjectTracks())
				{
					EXPECT_EQ(tr.num_features, 3);
					for (size_t i = 1; i < tr.poses.size(); ++i)
						EXPECT_LT(tr.poses[i - 1].step, tr.poses[i].step);
					for (const auto& p : tr.poses)
					{
						EXPECT_EQ(p.mean.size(), 3);
						EXPECT_TRUE(p.cov.allFinite());
					}
				}
			}
}

TEST(DynamicInvariants, ObjectPosesTrackGroundTruthNoiseFree)
{
	// Noise-free data: every object pose estimate equals the true motion of the object.
	dynslam_test::TinyScenarioOptions o;
	o.objects = 2;
	o.noise = false;
	o.cartesian_noise = true;
	o.steps = 20;
	const auto sc = dynslam_test::makeTinyScenario(o);
	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.reset();
	for (size_t k = 0; k < sc.actions.size(); ++k)
		f.processActionObservation(sc.actions[k], sc.frames[k]);
	const auto tracks = f.getObjectTracks();
	ASSERT_EQ(tracks.size(), 2u);
	for (const auto& [obj, tr] : tracks)
		for (const auto& p : tr.poses)
		{
			// The tiny scenario rotates object a by 0.03 (a + 1) rad per step.
			const int dk = p.step - tr.first_step;
			EXPECT_NEAR(p.mean[2], 0.03 * (obj + 1) * dk, 1e-5)
			    << "object " << obj << " step " << p.step;
		}
	const auto ego = f.getEgoPose();
	EXPECT_NEAR(ego.mean.x(), sc.ego.back()[0], 1e-4);
	EXPECT_NEAR(ego.mean.y(), sc.ego.back()[1], 1e-4);
}

TEST(DynamicInvariants, DropsStaticLandmarksOutOfRange)
{
	dynslam_test::TinyScenarioOptions o;
	o.landmarks = 25;
	o.steps = 60;
	o.range = 8;
	const auto sc = dynslam_test::makeTinyScenario(o);
	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = o.Sigma_rb;
	f.options.drop_static_after_unseen_steps = 5;
	f.reset();
	size_t dropped = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		f.processActionObservation(sc.actions[k], sc.frames[k]);
		dropped += f.getLastStepReport().dropped_static;
		checkInvariants(f, k);
	}
	EXPECT_GT(dropped, 0u);
	size_t inState = 0, recorded = 0;
	for (const auto& l : allStaticLandmarks(f)) (l.in_state ? inState : recorded)++;
	EXPECT_EQ(recorded, dropped);
	EXPECT_LT(inState, 25u);
}
