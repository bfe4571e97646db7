// Table I metrics on hand-made data with known answers.
#include <dynslam/eval/metrics.h>
#include <gtest/gtest.h>

#include <cmath>

#include "eval_test_data.h"

using namespace dynslam::eval;

namespace
{
TEgoEstimate ego(int step, const Eigen::Vector3d& mean, double var = 1e-2)
{
	TEgoEstimate e;
	e.step = step;
	e.mean = mean;
	e.cov = var * Eigen::Matrix3d::Identity();
	return e;
}
}  // namespace

TEST(Metrics, EgoRmseAteAndAngleWrap)
{
	const auto gt = eval_test::smallGroundTruth();
	TRunEstimates est;
	// Errors (x, y, theta): (0.1, 0, 0), (0, -0.2, 0.01), (0.3, 0.4, 0), (0, 0, +0.02 across pi).
	est.ego.push_back(ego(0, {0.1, 0, 0}));
	est.ego.push_back(ego(1, {1, -0.2, 0.11}));
	est.ego.push_back(ego(2, {2.3, 0.9, 0.2}));
	est.ego.push_back(ego(3, {3, 1, -M_PI + 0.01}));  // true heading pi - 0.01: error +0.02
	est.ego.push_back(ego(9, {0, 0, 0}));             // outside the ground truth
	const TRunMetrics m = computeRunMetrics(gt, est);
	EXPECT_EQ(m.ego.n_xy, 4u);
	EXPECT_EQ(m.ego_skipped, 1u);
	EXPECT_NEAR(m.ego.x, std::sqrt((0.01 + 0.09) / 4), 1e-12);
	EXPECT_NEAR(m.ego.y, std::sqrt((0.04 + 0.16) / 4), 1e-12);
	EXPECT_NEAR(m.ego.theta, std::sqrt((1e-4 + 4e-4) / 4), 1e-12);
	// ATE: position errors 0.1, 0.2, 0.5, 0.
	EXPECT_NEAR(m.ate, std::sqrt((0.01 + 0.04 + 0.25) / 4), 1e-12);
}

TEST(Metrics, PoseErrorWrapsAngles)
{
	const Eigen::Vector3d e = poseError({0, 0, -3.1}, {0, 0, 3.1});
	EXPECT_NEAR(e[2], 2 * M_PI - 6.2, 1e-12);
	EXPECT_NEAR(poseError({0, 0, 3.1}, {0, 0, -3.1})[2], -(2 * M_PI - 6.2), 1e-12);
	EXPECT_NEAR(poseError({1, 2, 0.5}, {0.5, 3, 0.25})[1], -1.0, 1e-15);
}

TEST(Metrics, StaticMapExcludesAndCountsMissingAndUnmatched)
{
	const auto gt = eval_test::smallGroundTruth();
	TRunEstimates est;
	est.landmarks.push_back({1, {10.3, 5.0}, Eigen::Matrix2d::Identity()});
	est.landmarks.push_back({2, {20.0, -5.4}, Eigen::Matrix2d::Identity()});
	est.landmarks.push_back({100000, {7, 2}, Eigen::Matrix2d::Identity()});  // a moving feature
	const TRunMetrics m = computeRunMetrics(gt, est);
	EXPECT_EQ(m.static_map.n_xy, 2u);
	EXPECT_EQ(m.landmarks_missing, 1u);    // ID 5
	EXPECT_EQ(m.landmarks_unmatched, 1u);  // ID 100000
	EXPECT_NEAR(m.static_map.x, std::sqrt(0.09 / 2), 1e-12);
	EXPECT_NEAR(m.static_map.y, std::sqrt(0.16 / 2), 1e-12);
	EXPECT_TRUE(std::isnan(m.static_map.theta));
	EXPECT_TRUE(std::isnan(m.ego.x));  // no ego estimates
}

TEST(Metrics, ObjectFeaturesAtFirstSightingAndPoses)
{
	const auto gt = eval_test::smallGroundTruth();
	TRunEstimates est;
	// Object 0 first seen at step 1: features (6, 2), (8, 2).
	est.object_features.push_back({0, 0, {6.2, 2.0}, Eigen::Matrix2d::Identity()});
	est.object_features.push_back({0, 1, {8.0, 1.9}, Eigen::Matrix2d::Identity()});
	// Object 1 feature 0 at step 0: (0, -3); feature 1 does not exist.
	est.object_features.push_back({1, 0, {0.0, -3.3}, Eigen::Matrix2d::Identity()});
	est.object_features.push_back({1, 1, {0.0, -3.0}, Eigen::Matrix2d::Identity()});
	est.object_features.push_back({7, 0, {0.0, 0.0}, Eigen::Matrix2d::Identity()});
	auto pose = [](int obj, int step, Eigen::VectorXd mean)
	{
		TObjectPoseEstimate p;
		p.object = obj;
		p.step = step;
		p.cov = Eigen::MatrixXd::Identity(mean.size(), mean.size());
		p.mean = std::move(mean);
		return p;
	};
	est.object_poses.push_back(pose(0, 1, Eigen::Vector3d(0.1, 0, 0.02)));
	est.object_poses.push_back(pose(0, 2, Eigen::Vector3d(1.0, 0.3, -0.02)));
	est.object_poses.push_back(pose(0, 0, Eigen::Vector3d(0, 0, 0)));   // before first sighting
	est.object_poses.push_back(pose(1, 2, Eigen::Vector2d(0.4, 1.0)));  // translation-only
	const TRunMetrics m = computeRunMetrics(gt, est);
	ASSERT_EQ(m.objects.size(), 2u);
	const auto& o0 = m.objects[0];
	EXPECT_EQ(o0.object, 0);
	EXPECT_FALSE(o0.translation_only);
	EXPECT_NEAR(o0.features.x, std::sqrt(0.04 / 2), 1e-12);
	EXPECT_NEAR(o0.features.y, std::sqrt(0.01 / 2), 1e-12);
	EXPECT_EQ(o0.features_missing, 0u);
	EXPECT_EQ(o0.poses.n_xy, 2u);
	EXPECT_EQ(o0.poses_skipped, 1u);
	EXPECT_NEAR(o0.poses.x, std::sqrt(0.01 / 2), 1e-12);
	EXPECT_NEAR(o0.poses.y, std::sqrt(0.09 / 2), 1e-12);
	EXPECT_NEAR(o0.poses.theta, 0.02, 1e-12);
	const auto& o1 = m.objects[1];
	EXPECT_TRUE(o1.translation_only);
	EXPECT_NEAR(o1.features.y, 0.3, 1e-12);
	EXPECT_EQ(o1.features.n_xy, 1u);
	EXPECT_NEAR(o1.poses.x, 0.4, 1e-12);
	EXPECT_NEAR(o1.poses.y, 0.0, 1e-12);
	EXPECT_TRUE(std::isnan(o1.poses.theta));
	EXPECT_EQ(m.object_estimates_unmatched, 2u);  // object 1 feature 1, object 7
}

TEST(Metrics, ObjectPoseHeadingErrorWrapsAcrossPi)
{
	// Object 0's true relative heading near +pi, estimates just across -pi: the errors are
	// +0.02 and -0.03, not 2 pi - 0.02 (an unwrapped difference would give an RMSE near 6.3).
	auto gt = eval_test::smallGroundTruth();
	gt.objects[0].pose[2] = Eigen::Vector3d(1, 0, M_PI - 0.01);
	gt.objects[0].pose[3] = Eigen::Vector3d(2, 0, -M_PI + 0.01);
	TRunEstimates est;
	TObjectPoseEstimate p;
	p.object = 0;
	p.cov = Eigen::Matrix3d::Identity();
	p.step = 2;
	p.mean = Eigen::Vector3d(1, 0, -M_PI + 0.01);  // error +0.02 across the cut
	est.object_poses.push_back(p);
	p.step = 3;
	p.mean = Eigen::Vector3d(2, 0, M_PI - 0.02);  // error -0.03 across the cut
	est.object_poses.push_back(p);
	const TRunMetrics m = computeRunMetrics(gt, est);
	ASSERT_EQ(m.objects.size(), 2u);
	EXPECT_EQ(m.objects[0].poses.n_theta, 2u);
	EXPECT_NEAR(m.objects[0].poses.theta, std::sqrt((0.02 * 0.02 + 0.03 * 0.03) / 2), 1e-12);
	EXPECT_NEAR(m.objects[0].poses.x, 0.0, 1e-15);
}

TEST(Metrics, EgoErrorRowsWithThreeSigma)
{
	const auto gt = eval_test::smallGroundTruth();
	std::vector<TEgoEstimate> e = {ego(2, {2.3, 0.9, 0.2}, 0.04), ego(0, {0.1, 0, 0}, 0.01)};
	const auto rows = egoErrors(gt, e);
	ASSERT_EQ(rows.size(), 2u);
	EXPECT_EQ(rows[0].step, 0);
	EXPECT_EQ(rows[1].step, 2);
	EXPECT_DOUBLE_EQ(rows[1].t, 1.0);
	EXPECT_NEAR(rows[1].error[1], 0.4, 1e-12);
	EXPECT_NEAR(rows[1].sigma3[0], 0.6, 1e-12);
	EXPECT_NEAR(rows[0].sigma3[2], 0.3, 1e-12);
}

TEST(Metrics, RejectsMalformedInput)
{
	const auto gt = eval_test::smallGroundTruth();
	TRunEstimates est;
	est.ego = {ego(1, {0, 0, 0}), ego(1, {0, 0, 0})};
	EXPECT_THROW(computeRunMetrics(gt, est), std::invalid_argument);
	est.ego.clear();
	TObjectPoseEstimate p;
	p.mean = Eigen::VectorXd::Zero(4);
	p.cov = Eigen::MatrixXd::Zero(4, 4);
	est.object_poses.push_back(p);
	EXPECT_THROW(computeRunMetrics(gt, est), std::invalid_argument);
	est.object_poses.clear();
	est.nis = {1.0};
	EXPECT_THROW(computeRunMetrics(gt, est), std::invalid_argument);
	est.nis.clear();
	auto bad = gt;
	bad.objects[0].pose.pop_back();
	EXPECT_THROW(computeRunMetrics(bad, est), std::invalid_argument);
}

TEST(Metrics, DivergedEstimateNamesWhatDiverged)
{
	// dynslam-compare leaves a diverged filter out of its table with this text (MRPT's
	// static filter on KITTI 0007 reaches NaN at step 766; doc/kitti.md)
	TRunEstimates est;
	est.ego = {ego(0, {0, 0, 0}), ego(1, {1, 0, 0}), ego(2, {2, 0, 0})};
	TLandmarkEstimate l;
	l.id = 7;
	est.landmarks = {l};
	TObjectPoseEstimate p;
	p.object = 1;
	p.step = 2;
	p.mean = Eigen::Vector3d::Zero();
	p.cov = Eigen::Matrix3d::Identity();
	est.object_poses = {p};
	EXPECT_EQ(divergedEstimate(est), "");
	est.object_poses[0].mean.x() = -kDivergedMagnitude;  // the limit itself is still sane
	EXPECT_EQ(divergedEstimate(est), "");
	est.object_poses[0].mean.x() = std::nan("");
	EXPECT_EQ(divergedEstimate(est), "pose of object 1 at step 2");
	est.landmarks[0].mean.y() = -INFINITY;
	EXPECT_EQ(divergedEstimate(est), "mean of landmark 7");
	est.ego[2].mean.z() = std::nan("");
	EXPECT_EQ(divergedEstimate(est), "ego mean at step 2");
	est.ego[1].mean.x() = 2e9;  // finite but beyond any map
	EXPECT_EQ(divergedEstimate(est), "ego mean at step 1");
	EXPECT_THROW(computeRunMetrics(eval_test::smallGroundTruth(), est), std::invalid_argument);
}
