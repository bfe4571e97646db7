#pragma once
/** @file detection_simulator.h
 * A synthetic 3-D detector for tests (issue 31, item 7: the project makes its own detection
 * files): PointRCNN/AB3DMOT-format detections (detection_files.h) from KITTI labels, with seeded
 * misses, false positives, jitter and front/back flips; and the writers of the 15-column format
 * and of a nominal calibration file. Pure C++/Eigen. `dynslam-kitti --simulate-detections DIR`
 * (CKittiApp.h) calls it with the INI section [KITTI_SimulateDetections] (doc/kitti.md, section
 * 1, "Simulated detections").
 *
 * Model, per frame k = 0 .. numFrames-1, in this draw order (one MT19937 seeded with `seed`):
 *  - every label box of type Car, Pedestrian or Cyclist (the detector's classes; Van, Truck, ...
 *    are not detected, as PointRCNN's Car class does not include them) at frame k, in file order:
 *    one uniform u: missed if u < miss_probability; if kept, normals added to the camera x and z
 *    of the bottom centre (std_xy [m]), to rot_y (std_yaw [rad]) and to l, w, h (std_size [m],
 *    each clamped to >= 0.1 m); one uniform: rot_y + pi if < flip_probability (wrapped to
 *    (-pi, pi]); the score uniform in [score_min, score_max]. A box is drawn whether or not it
 *    is in the importer's range (the importer filters);
 *  - then n ~ Poisson(false_positives_per_frame) false positives, class Car: range uniform in
 *    [fp_min_range, fp_max_range], bearing uniform in +-fp_fov_deg/2 (ego frame: forward, left),
 *    rot_y uniform in (-pi, pi], l, w, h = 3.9, 1.6, 1.5 m, score uniform in
 *    [fp_score_min, fp_score_max]; bottom at camera y = 1.65 m.
 * The 2-D box is written as 0, 0, 0, 0 (not simulated); alpha = rot_y - atan2(x, z) (KITTI's
 * observation angle). With every probability and std 0 the detections are the labels' boxes
 * exactly (17 significant digits). */
#include <dynslam/kitti/detection_files.h>
#include <dynslam/kitti/kitti_files.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::kitti
{
struct TDetectionSimOptions
{
	uint32_t seed = 1;
	double miss_probability = 0;                   ///< in [0, 1]
	double false_positives_per_frame = 0;          ///< Poisson mean, >= 0
	double fp_min_range = 5, fp_max_range = 40;    ///< [m], 0 <= min <= max
	double fp_fov_deg = 90;                        ///< [deg] in (0, 360]
	double fp_score_min = -1, fp_score_max = 1;    ///< uniform score of a false positive
	double score_min = 2, score_max = 10;          ///< uniform score of a true detection
	double std_xy = 0, std_yaw = 0, std_size = 0;  ///< jitter [m], [rad], [m], >= 0
	double flip_probability = 0;                   ///< in [0, 1]
};

/** Throws std::invalid_argument naming the option for a value out of its range. */
void checkDetectionSimOptions(const TDetectionSimOptions& o);

/** The detections of frames 0 .. numFrames-1 (labels beyond: std::invalid_argument), by
 * frame, each frame's true detections (label order) before its false positives. `line` = the
 * 1-based line in its class file as written by writeDetectionFiles. */
std::vector<TKittiDetection> simulateDetections(const TKittiLabels& labels, size_t numFrames,
                                                const TDetectionSimOptions& o);

/** One line of the 15-column format (17 significant digits). */
std::string detectionLine(const TKittiDetection& d);

/** Writes DIR/CLASS/SSSS.txt for Pedestrian, Car and Cyclist (empty files for a class without
 * detections; folders created). Throws std::runtime_error if a file cannot be written, and
 * std::invalid_argument for a detection whose class is not one of the three. */
void writeDetectionFiles(const std::vector<TKittiDetection>& dets, const std::string& dir,
                         const std::string& sequence);

/** Writes a nominal calibration DIR/SSSS.txt that readCalib accepts (made-up pinhole
 * projections, identity rotations; the importer checks it and does not use it). */
void writeNominalCalib(const std::string& dir, const std::string& sequence);
}  // namespace dynslam::kitti
