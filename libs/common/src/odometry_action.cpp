/** @file odometry_action.cpp */
#include <dynslam/common/odometry_action.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>

namespace dynslam
{
mrpt::obs::CActionRobotMovement2D makeOdometryMovement(const Eigen::Vector3d& u,
                                                       const Eigen::Matrix3d& C,
                                                       mrpt::Clock::time_point t)
{
	mrpt::obs::CActionRobotMovement2D act;
	const mrpt::poses::CPose2D inc(u[0], u[1], u[2]);
	mrpt::math::CMatrixDouble33 cov;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) cov(i, j) = C(i, j);
	act.poseChange = mrpt::poses::CPosePDFGaussian::Create(inc, cov);
	act.rawOdometryIncrementReading = inc;
	act.estimationMethod = mrpt::obs::CActionRobotMovement2D::emScan2DMatching;
	act.timestamp = t;
	return act;
}

mrpt::obs::CActionCollection::Ptr makeOdometryAction(const Eigen::Vector3d& u,
                                                     const Eigen::Matrix3d& C,
                                                     mrpt::Clock::time_point t)
{
	auto acts = mrpt::obs::CActionCollection::Create();
	acts->insert(makeOdometryMovement(u, C, t));
	return acts;
}
}  // namespace dynslam
