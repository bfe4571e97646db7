#pragma once
/** @file object_world_estimate.h
 * What CDynamicKFSLAM2D reports of one object in the world frame (getObjectWorldPose,
 * getObjectVelocity; issue 30 item 5). The meaning of the pose is models/object_world_pose.h:
 * the reference point r = c0 + (dx, dy) (c0: the centroid of the object's founders, its
 * features seen at the first sighting, at that time) and the heading dtheta (the rotation
 * since the first sighting). */
#include <Eigen/Core>
#include <cstdint>
#include <optional>

namespace dynslam
{
/** An object's velocity (object_model = cv | ctrv | ca): (vx, vy, omega), the world-frame velocity
 * of the reference point r and the turn rate, or (vx, vy) for a one-feature object; marginal
 * covariance (with the prior gauge's output term, like every getter). */
struct TObjectVelocity
{
	int step = -1;  ///< step of the pose it belongs to (the object's newest)
	Eigen::VectorXd mean;
	Eigen::MatrixXd cov;
};

/** An object's pose in the world at its newest pose estimate. */
struct TObjectWorldPose
{
	int32_t object = -1;
	int step = -1;  ///< step of the pose xi used (the object's newest; its first sighting: xi = 0)
	/** (x, y, heading): r = c0 + (dx, dy) and dtheta, or (x, y) = f_0 + (dx, dy) for a
	 * one-feature object (no heading). */
	Eigen::VectorXd mean;
	/** Covariance of mean, propagated from the joint covariance of xi and the founders' f_0 by
	 * the Jacobian of models::objectWorldPose (exact: the map is linear). */
	Eigen::MatrixXd cov;
	/** The velocity (getObjectVelocity): empty for the paper's model (object_model = none),
	 * which has no velocity block. */
	std::optional<TObjectVelocity> velocity;
};
}  // namespace dynslam
