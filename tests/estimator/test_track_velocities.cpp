/** tracksFromRegistry attaches each recorded velocity to the dropped pose of its own step
 * (issue 13's object velocity RMSE reads them there); poses without one keep none. */
#include <dynslam/common/backend_results.h>
#include <gtest/gtest.h>

using namespace dynslam;

TEST(TrackVelocities, EachVelocityGoesToThePoseOfItsStep)
{
	estimator::CObjectRegistry reg;
	reg.registerObject(5, 2, {100}, {0});
	for (int step : {3, 4, 6})
	{
		estimator::TPoseRecord p;
		p.step = step;
		p.dim = 2;
		p.mean.head<2>() = Eigen::Vector2d(step, 0);
		reg.recordDroppedPose(5, p, true);
	}
	for (int step : {4, 5, 6})  // step 5 has no pose: not attached anywhere
	{
		estimator::TVelocityRecord v;
		v.step = step;
		v.dim = 2;
		v.velocity.head<2>() = Eigen::Vector2d(10.0 * step, 1);
		v.cov.topLeftCorner<2, 2>() = Eigen::Matrix2d::Identity() * step;
		reg.recordDroppedVelocity(5, v, true);
	}
	const auto tracks = tracksFromRegistry(reg);
	const auto& poses = tracks.at(5).poses;
	ASSERT_EQ(poses.size(), 3u);
	EXPECT_EQ(poses[0].velocity.size(), 0);
	ASSERT_EQ(poses[1].velocity.size(), 2);
	EXPECT_EQ(poses[1].velocity[0], 40.0);
	EXPECT_EQ(poses[1].velocity_cov(1, 1), 4.0);
	ASSERT_EQ(poses[2].velocity.size(), 2);
	EXPECT_EQ(poses[2].velocity[0], 60.0);
	// A velocity of the wrong size is a clear error.
	TObjectPoseEstimate e;
	e.step = 1;
	e.velocity = Eigen::VectorXd::Zero(4);
	e.velocity_cov = Eigen::MatrixXd::Zero(4, 4);
	EXPECT_THROW(toVelocityRecord(e), std::invalid_argument);
}

TEST(TrackVelocities, RecordsRoundTripPosesAndVelocitiesOfTwoAndThreeEntries)
{
	for (int d : {2, 3})
	{
		TObjectPoseEstimate e;
		e.step = 7;
		e.mean = Eigen::VectorXd::LinSpaced(d, 1.0, double(d));
		e.cov = Eigen::MatrixXd::Identity(d, d) * 0.5;
		e.cov(0, d - 1) = e.cov(d - 1, 0) = 0.1;
		e.velocity = Eigen::VectorXd::LinSpaced(d, 10.0, 10.0 + d);
		e.velocity_cov = e.cov * 2.0;
		const auto p = toRecord(e);
		const auto v = toVelocityRecord(e);
		EXPECT_EQ(p.step, 7);
		EXPECT_EQ(v.step, 7);
		ASSERT_EQ(p.dim, d);
		ASSERT_EQ(v.dim, d);
		const auto back = toEstimate(p);
		EXPECT_EQ(back.mean, e.mean);
		EXPECT_EQ(back.cov, e.cov);
		EXPECT_EQ(Eigen::VectorXd(v.velocity.head(d)), e.velocity);
		EXPECT_EQ(Eigen::MatrixXd(v.cov.topLeftCorner(d, d)), e.velocity_cov);
	}
	TObjectPoseEstimate bad;
	bad.mean = Eigen::VectorXd::Zero(3);
	bad.cov = Eigen::MatrixXd::Zero(2, 2);  // covariance of the wrong shape
	EXPECT_THROW(toRecord(bad), std::invalid_argument);
}
