#pragma once
/** @file bev_box.h
 * Oriented boxes in the bird's-eye view and their overlap (pure Eigen): the match criteria of
 * the multi-object tracking metrics (eval/mot_metrics.h; doc/metrics.md "Multi-object
 * tracking") and the BEV IoU cost of the box tracker (estimator/box_tracker.h).
 *
 * The intersection area is computed by clipping one footprint by the other (Sutherland-Hodgman:
 * both are convex) in double precision. OpenCV's cv::rotatedRectangleIntersection does the same
 * job but on cv::RotatedRect (float centre, size and angle in degrees) and is not linked by
 * libs/core (only libs/apps links OpenCV); at 1e-7 relative precision, boxes that share an edge
 * (adjacent parked cars) are where float clipping is fragile, so the project clips itself. */
#include <Eigen/Core>

namespace dynslam::models
{
/** A box footprint: centre (x, y) [m], heading yaw [rad] of the length axis, length along it
 * and width across it [m]. A heading and heading + pi describe the same footprint. */
struct TBevBox
{
	double x = 0, y = 0, yaw = 0, length = 0, width = 0;
};

/** The four corners, counter-clockwise: (+l/2, +w/2), (-l/2, +w/2), (-l/2, -w/2), (+l/2, -w/2)
 * in the box frame, placed by (x, y, yaw). */
Eigen::Matrix<double, 2, 4> bevCorners(const TBevBox& b);

/** Area of the intersection of the two footprints [m^2]. */
double bevIntersectionArea(const TBevBox& a, const TBevBox& b);

/** Intersection over union of the two footprints, in [0, 1]. Throws std::invalid_argument if
 * a box has a length or width that is not finite and > 0. */
double bevIoU(const TBevBox& a, const TBevBox& b);

/** Distance of the two centres [m]. */
double bevCentreDistance(const TBevBox& a, const TBevBox& b);
}  // namespace dynslam::models
