/** eval::objectVelocityErrors and trueObjectVelocity (issue 13, doc/metrics.md "Object
 * velocity"): the truth by central differences (one-sided at the ends), the RMSE of the speed
 * and turn-rate errors and the velocity ANEES, values computed by hand. */
#include <dynslam/eval/estimates.h>
#include <dynslam/eval/velocity_metrics.h>
#include <dynslam/eval/writers.h>
#include <gtest/gtest.h>
#include <velocity_estimate.h>

#include <cmath>
#include <sstream>

using namespace dynslam;
using namespace dynslam::eval;
using eval_test::withVelocity;

namespace
{
const double kPi = std::acos(-1.0);

/** Object 7, NaN before step 1, dt = 0.5 s, accelerating along x (dx = 0, 1, 3, 6 m) and turning
 * at 0.2 rad/s; its heading crosses +-pi between steps 2 and 3. */
io::TGroundTruth movingObject()
{
	io::TGroundTruth gt;
	io::TObjectGroundTruth o;
	o.object = 7;
	const double nan = std::nan("");
	const double dx[] = {nan, 0, 1, 3, 6};
	const double th[] = {nan, kPi - 0.15, kPi - 0.05, -kPi + 0.05, -kPi + 0.15};
	for (int k = 0; k < 5; ++k)
	{
		gt.t.push_back(0.5 * k);
		gt.ego.emplace_back(0, 0, 0);
		o.pose.emplace_back(dx[k], k == 0 ? nan : 2.0, th[k]);
	}
	gt.objects.push_back(o);
	return gt;
}

}  // namespace

TEST(VelocityMetrics, TruthByCentralAndOneSidedDifferences)
{
	const io::TGroundTruth gt = movingObject();
	const io::TObjectGroundTruth& o = gt.objects[0];
	EXPECT_FALSE(trueObjectVelocity(o, gt.t, 0));    // NaN pose
	EXPECT_FALSE(trueObjectVelocity(o, gt.t, 5));    // beyond the truth
	const auto v1 = trueObjectVelocity(o, gt.t, 1);  // forward: step 0 is NaN
	const auto v2 = trueObjectVelocity(o, gt.t, 2);  // central, across +-pi
	const auto v4 = trueObjectVelocity(o, gt.t, 4);  // backward: the last step
	ASSERT_TRUE(v1 && v2 && v4);
	EXPECT_LT((*v1 - Eigen::Vector3d(2, 0, 0.2)).norm(), 1e-12);
	EXPECT_LT((*v2 - Eigen::Vector3d(3, 0, 0.2)).norm(), 1e-12);
	EXPECT_LT((*v4 - Eigen::Vector3d(6, 0, 0.2)).norm(), 1e-12);
	io::TObjectGroundTruth single;
	single.pose = {Eigen::Vector3d(1, 2, 0)};
	EXPECT_FALSE(trueObjectVelocity(single, {0.0}, 0));  // no second pose: no velocity
}

TEST(VelocityMetrics, RmseAneesAndSkips)
{
	const io::TGroundTruth gt = movingObject();
	TRunEstimates est;
	EXPECT_FALSE(objectVelocityErrors(gt, est));  // no velocity anywhere: nothing to score
	// Step 1: error (0.3, 0.4, 0.1): speed 0.5, NEES 0.36 + 0.64 + 1 = 2.
	est.object_poses.push_back(
	    withVelocity(7, 1, Eigen::Vector3d(2.3, 0.4, 0.3), Eigen::Vector3d(0.25, 0.25, 0.01)));
	// Step 3 (truth (5, 0, 0.2)): error (0, 0, -0.2), NEES 1.
	est.object_poses.push_back(
	    withVelocity(7, 3, Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(1, 1, 0.04)));
	// Step 4: exact, zero covariance: scored, left out of the ANEES.
	est.object_poses.push_back(
	    withVelocity(7, 4, Eigen::Vector3d(6, 0, 0.2), Eigen::Vector3d::Zero()));
	// Skipped: step 0 (NaN truth) and an object the truth does not have.
	est.object_poses.push_back(
	    withVelocity(7, 0, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Ones()));
	est.object_poses.push_back(
	    withVelocity(9, 2, Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::Ones()));
	// A pose without a velocity (paper's model): not counted at all.
	TObjectPoseEstimate plain =
	    withVelocity(7, 2, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
	plain.velocity.resize(0);
	plain.velocity_cov.resize(0, 0);
	est.object_poses.push_back(plain);
	checkEstimates(est);

	const auto e = objectVelocityErrors(gt, est);
	ASSERT_TRUE(e);
	EXPECT_EQ(e->n, 3u);
	EXPECT_EQ(e->n_omega, 3u);
	EXPECT_EQ(e->skipped, 2u);
	EXPECT_NEAR(e->speed_rmse, std::sqrt(0.25 / 3), 1e-12);
	EXPECT_NEAR(e->omega_rmse, std::sqrt((0.01 + 0.04) / 3), 1e-12);
	EXPECT_NEAR(e->anees, (2.0 + 1.0) / 6.0, 1e-12);
	ASSERT_EQ(e->speed_rmse_per_object.count(7), 1u);
	EXPECT_NEAR(e->speed_rmse_per_object.at(7), std::sqrt(0.25 / 3), 1e-12);

	// metrics.csv: 4 trailing columns, empty for a row without velocities.
	std::vector<TMetricsRow> rows(2);
	rows[0].filter = "dynamic";
	rows[1].filter = "dynamic_cv";
	rows[1].velocity = e;
	std::ostringstream os;
	writeMetricsCsv(os, rows);
	std::istringstream is(os.str());
	std::string header, r0, r1;
	std::getline(is, header);
	std::getline(is, r0);
	std::getline(is, r1);
	const std::string cols = ",obj_speed_rmse,obj_omega_rmse,obj_velocity_anees,obj_velocity_n";
	ASSERT_GE(header.size(), cols.size());
	EXPECT_EQ(header.substr(header.size() - cols.size()), cols);
	EXPECT_EQ(r0.substr(r0.size() - 4), ",,,,");
	EXPECT_EQ(r1.substr(r1.size() - 2), ",3");
}

TEST(VelocityMetrics, BadVelocityShapesAreRejected)
{
	TRunEstimates est;
	est.object_poses.push_back(
	    withVelocity(7, 1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()));
	est.object_poses.back().velocity_cov = Eigen::Matrix2d::Identity();
	EXPECT_THROW(checkEstimates(est), std::invalid_argument);
	est.object_poses.back().velocity_cov = Eigen::Matrix3d::Identity();
	est.object_poses.back().velocity[1] = std::nan("");
	EXPECT_THROW(checkEstimates(est), std::invalid_argument);
	est.object_poses.back().velocity = Eigen::Vector2d::Zero();  // 2 entries for a 3-dof pose
	est.object_poses.back().velocity_cov = Eigen::Matrix2d::Identity();
	EXPECT_THROW(checkEstimates(est), std::invalid_argument);
}
