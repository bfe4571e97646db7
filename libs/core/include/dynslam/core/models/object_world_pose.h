#pragma once
/** @file object_world_pose.h
 * An object's pose in the world from the filter's object state (issue 30 item 5).
 *
 * The filter's object pose xi = (dx, dy, dtheta) is the motion since the object's first
 * sighting (object_pose.h): a rotation by dtheta about c0, the centroid of the founders' time-0
 * features f_0 (its features seen at the first sighting), followed by the translation (dx, dy).
 * The object's body frame is the world frame at its first sighting, placed at c0. Its pose in
 * the world at time t is that frame moved by xi:
 *
 *     w = (c0 + (dx, dy), dtheta),   c0 = mean_k f_0,k (k over the founders),
 *
 * i.e. the reference point r = c0 + (dx, dy) (where the founders' centroid is now: the point
 * that object_model = cv | ctrv give a world velocity to) and the heading dtheta: the rotation
 * since the first sighting (the heading of the body frame, whose axes are the world's at time
 * 0). A one-feature object (xi = (dx, dy)) has no heading: w = f_0 + (dx, dy) = its f_t.
 * w is linear in (xi, f_0): J_w_xi = I, J_w_f0 = [I/n ... I/n; 0]. */
#include <Eigen/Core>

namespace dynslam::models
{
/** w = (c0 + (dx, dy)[, dtheta]) of the d-vector xi (d = 2 or 3) and the founders' f_0
 * (2 x n, n >= 1). J_w_in (d x (d + 2n)): d w / d [xi; vec(f0)]. Throws
 * std::invalid_argument on a wrong size or no founder. */
Eigen::VectorXd objectWorldPose(const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0,
                                Eigen::MatrixXd* J_w_in = nullptr);
}  // namespace dynslam::models
