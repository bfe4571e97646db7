#pragma once
/** @file geometry.h
 * KITTI camera frame -> the bird's-eye (2-D) frames of the importer (pure Eigen).
 *
 * Camera frame: x right, y down, z forward. The ground plane is the camera's x-z plane:
 *  - a camera-frame point (x, y, z) is the ego-frame point (z, -x) (forward, left);
 *  - the ego pose of camera-to-world [R t] is (t_z, -t_x, atan2(-R_02, R_22)): position of the
 *    camera in that plane, heading = the direction of the camera's z axis in it, i.e. minus
 *    the rotation about the camera's y axis (y is "down", so a left turn is a negative
 *    rotation about y). Pitch and roll are dropped.
 *  - a box's yaw in the ego frame is -rotation_y - pi/2 (its length axis, KITTI's object x
 *    axis, is (cos ry, 0, -sin ry) in the camera).
 * World 2-D frame: the ego frame of frame 0 (the camera of frame 0 is the identity). A point
 * seen at frame k is placed in the world by the 2-D ego pose: p_w = ego_k (+) p_ego. */
#include <dynslam/kitti/kitti_files.h>

#include <Eigen/Core>

namespace dynslam::kitti
{
/** (x, y, theta) of a camera-to-world pose in the ground plane. */
Eigen::Vector3d egoPoseFromCamera(const TCameraPose& T);
/** Camera-frame (x, z) -> ego-frame (forward, left) = (z, -x). */
Eigen::Vector2d cameraToEgo(double x_cam, double z_cam);
/** Yaw of a box's length axis in the ego frame: -ry - pi/2, wrapped to (-pi, pi]. */
double boxYawEgo(double ry);
/** The box's footprint centre in the ego frame. */
Eigen::Vector2d boxCentreEgo(const TKittiBox& b);
/** The four footprint corners in the ego frame, columns in this order (box frame: u along the
 * length, v = u rotated +90 deg): (+l/2, +w/2), (+l/2, -w/2), (-l/2, -w/2), (-l/2, +w/2). */
Eigen::Matrix<double, 2, 4> footprintCornersEgo(const TKittiBox& b);
/** p_w = pose (+) p (2-D point composition). */
Eigen::Vector2d egoToWorld(const Eigen::Vector3d& pose, const Eigen::Vector2d& p);
/** Range and bearing of an ego-frame point. */
Eigen::Vector2d rangeBearing(const Eigen::Vector2d& p);
}  // namespace dynslam::kitti
