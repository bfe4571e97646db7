#pragma once
/** @file box_ground_truth.h
 * The box truth of an imported KITTI sequence (issue 31: the multi-object tracking metrics),
 * read from the importer's `<base>_gt_tracks.csv` (step,t,track,type,moving,read,x,y,yaw: per
 * annotated frame of every track, the footprint centre and heading in the world frame of the
 * ground truth) and `<base>_gt_track_list.csv` (per track: ...,length,width; header names the
 * columns), both written by dynslam-kitti (libs/kitti rawlog_writer.h). */
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::io
{
/** One annotated box of one step. */
struct TTruthBox
{
	int step = 0;
	int32_t track = -1;
	std::string type;  ///< the label's type (Car, Van, Pedestrian, ...)
	Eigen::Vector3d world = Eigen::Vector3d::Zero();   ///< centre x, y [m], heading [rad]
	Eigen::Vector2d extent = Eigen::Vector2d::Zero();  ///< length, width [m]
};

/** Whether `<base>_gt_tracks.csv` and `<base>_gt_track_list.csv` both exist. */
bool hasBoxGroundTruth(const std::string& base);

/** Every annotated box, in file order. Throws std::runtime_error "FILE:LINE: what" for a
 * missing file or column, a value that does not parse, a track of the tracks file missing from
 * the track list, a length or width <= 0, or a negative step. */
std::vector<TTruthBox> readBoxGroundTruth(const std::string& base);
}  // namespace dynslam::io
