#pragma once
/** @file se2.h
 * SE(2) odometry model: x_{t+1} = x_t (+) u, with u the odometry increment in the robot frame
 * (MRPT's CActionRobotMovement2D convention, CPose2D::operator+).
 *
 * The paper (Appendix C) adds a global increment, g(x) = x + x_odom. With the heading near 0
 * (the highway) both agree to first order; we follow MRPT so the static baseline
 * CRangeBearingKFSLAM2D and the dynamic filter share one motion model. */
#include <Eigen/Core>

namespace dynslam::models
{
/** Wrap an angle to (-pi, pi]. */
double wrapToPi(double a);

/** 2-D rotation matrix R(theta). */
Eigen::Matrix2d rot2(double theta);
/** dR/dtheta. */
Eigen::Matrix2d rot2Derivative(double theta);

/** Pose composition out = x (+) u, angle wrapped.
 * J_out_x = d out / d x (3x3), J_out_u = d out / d u (3x3). */
Eigen::Vector3d composePose(const Eigen::Vector3d& x, const Eigen::Vector3d& u,
                            Eigen::Matrix3d* J_out_x = nullptr, Eigen::Matrix3d* J_out_u = nullptr);

/** Inverse composition u = b (-) a (the increment that takes a to b), angle wrapped. */
Eigen::Vector3d poseDifference(const Eigen::Vector3d& b, const Eigen::Vector3d& a);
}  // namespace dynslam::models
