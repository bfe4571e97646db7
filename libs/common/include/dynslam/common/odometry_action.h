#pragma once
/** @file odometry_action.h
 * The MRPT action every writer of this project stores for one odometry step. */
#include <mrpt/core/Clock.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>

#include <Eigen/Core>

namespace dynslam
{
/** A CActionRobotMovement2D holding the increment u = (dx, dy, dphi) with covariance C:
 * poseChange = CPosePDFGaussian(u, C), rawOdometryIncrementReading = u, the timestamp t, and
 * estimationMethod = emScan2DMatching. Not emOdometry: MRPT serializes an emOdometry action as
 * the raw increment plus its own motion-model parameters and rebuilds the covariance from
 * those when the rawlog is read, so C would be lost for every reader of the file; any other
 * method stores the PDF itself. */
mrpt::obs::CActionRobotMovement2D makeOdometryMovement(const Eigen::Vector3d& u,
                                                       const Eigen::Matrix3d& C,
                                                       mrpt::Clock::time_point t = {});
/** The same in a new action collection. */
mrpt::obs::CActionCollection::Ptr makeOdometryAction(const Eigen::Vector3d& u,
                                                     const Eigen::Matrix3d& C,
                                                     mrpt::Clock::time_point t = {});
}  // namespace dynslam
