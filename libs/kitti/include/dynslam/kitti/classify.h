#pragma once
/** @file classify.h
 * Static or moving: the rule of the KITTI importer (doc/kitti.md, section 3). Whether an object
 * moves is not in the labels; it is derived from the footprint's positions in the world frame,
 * never from the object type:
 *
 *   radius = max_k | c_k - mean_k(c_k) |   over every annotated frame k of the track
 *   moving  <=>  radius > static_radius
 *
 * c_k = the footprint centre placed in the world by the ego pose of frame k (geometry.h). The
 * radius of a parked car is the annotation jitter plus the drift of the camera trajectory; the
 * threshold (config/kitti.ini, static_radius) was read off the distribution of radii over the
 * eleven development sequences. */
#include <Eigen/Core>
#include <vector>

namespace dynslam::kitti
{
/** Largest distance of the points from their mean (0 for fewer than two points). */
double footprintRadius(const std::vector<Eigen::Vector2d>& centres);
/** The rule: radius > static_radius. */
inline bool isMoving(double radius, double static_radius) { return radius > static_radius; }
}  // namespace dynslam::kitti
