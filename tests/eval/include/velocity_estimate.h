#pragma once
// An object-pose estimate that carries only a velocity (its pose at the origin, unit pose
// covariance), shared by the eval tests of the velocity scores.
#include <dynslam/eval/estimates.h>

#include <Eigen/Core>

namespace eval_test
{
/** Object `obj` at `step` with velocity `v` (2 or 3 entries) and diagonal variances `var`. */
inline dynslam::eval::TObjectPoseEstimate withVelocity(int32_t obj, int step,
                                                       const Eigen::VectorXd& v,
                                                       const Eigen::VectorXd& var)
{
	dynslam::eval::TObjectPoseEstimate p;
	p.object = obj;
	p.step = step;
	p.mean = Eigen::Vector3d::Zero();
	p.cov = Eigen::Matrix3d::Identity();
	p.velocity = v;
	p.velocity_cov = var.asDiagonal();
	return p;
}
}  // namespace eval_test
