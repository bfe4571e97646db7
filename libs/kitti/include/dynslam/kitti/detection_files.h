#pragma once
/** @file detection_files.h
 * Readers of 3-D detector output and KITTI calibration files (pure C++/Eigen, no MRPT):
 *
 * - Detections (the PointRCNN boxes published with AB3DMOT, one folder per class,
 *   CLASS/SSSS.txt): one detection per line, 15 comma-separated columns
 *   `frame, class, x1, y1, x2, y2, score, h, w, l, x, y, z, rot_y, alpha`; class 1 Pedestrian,
 *   2 Car, 3 Cyclist (it must be the class of the folder); x1..y2 the 2-D box [px]; score the
 *   detector's confidence (no range imposed); h, w, l the box size [m] (> 0); x, y, z the
 *   bottom centre in the rectified camera frame (as the labels, kitti_files.h); rot_y the yaw
 *   about the camera's y axis [rad]. No track IDs.
 * - Calibration (calib/SSSS.txt): lines `KEY: numbers`, P0..P3 (3x4, 12 numbers), R0_rect
 *   (3x3, 9; also spelled R_rect), Tr_velo_to_cam and Tr_imu_to_velo (3x4, 12; also spelled
 *   Tr_velo_cam, Tr_imu_velo). Each key exactly once; unknown keys are errors; the 3x3 blocks of
 *   R0_rect, Tr_velo_to_cam and Tr_imu_to_velo must be rotations (|R^T R - I| <= 1e-3).
 * Every error throws std::runtime_error "FILE:LINE: what" (or "FILE: what" for a missing file
 * or key; in a calibration line, "column j" is the j-th number after the key): wrong column count,
 * an empty or non-numeric token, NaN/Inf, a negative or non-integer frame, an unknown class code or
 * one of another folder, a size <= 0, a frame beyond the sequence (checkDetectionsAgainstFrames).
 */
#include <dynslam/kitti/kitti_files.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace dynslam::kitti
{
/** One detected box. */
struct TKittiDetection
{
	int frame = 0;
	std::string type;  ///< Pedestrian, Car or Cyclist
	double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
	double score = 0;
	double h = 0, w = 0, l = 0;  ///< height, width, length [m]
	double x = 0, y = 0, z = 0;  ///< bottom centre, camera frame [m]
	double ry = 0, alpha = 0;    ///< [rad]
	int line = 0;                ///< line in the file
};

/** The detections of one class file. */
struct TKittiDetectionFile
{
	std::string file, type;
	std::vector<TKittiDetection> detections;  ///< in file order
	int max_frame = -1;                       ///< largest frame (-1: empty file)
	int max_frame_line = 0;
};

/** The detector's class code: 1 Pedestrian, 2 Car, 3 Cyclist; "" for any other. */
std::string detectionClassName(int code);

/** Reads one class file; `type` is the folder's class (Pedestrian, Car or Cyclist). Throws
 * std::runtime_error naming file and line. An empty file is no error (no detections). */
TKittiDetectionFile readDetections(const std::string& path, const std::string& type);

/** Throws std::runtime_error naming the detection file and line if a frame >= numFrames (the
 * sequence's frames: the lines of `posesPath`). */
void checkDetectionsAgainstFrames(const TKittiDetectionFile& d, size_t numFrames,
                                  const std::string& posesPath);

/** KITTI calibration of one sequence. */
struct TKittiCalib
{
	std::array<Eigen::Matrix<double, 3, 4>, 4> P;  ///< projections of cameras 0-3
	Eigen::Matrix3d R0_rect;                       ///< rectifying rotation
	Eigen::Matrix<double, 3, 4> Tr_velo_to_cam, Tr_imu_to_velo;
};

/** Reads a calibration file. Throws std::runtime_error naming file and line (or key). */
TKittiCalib readCalib(const std::string& path);

/** Options of the detection reader ([KITTI_Import] keys detection_classes and
 * detection_min_score; CKittiOptions.h). */
struct TDetectionOptions
{
	/** Classes read, one file each (DIR/CLASS/SSSS.txt). */
	std::vector<std::string> classes{"Car"};
	/** Detections with score >= this are kept; -infinity (INI: none) keeps all. */
	double min_score = -std::numeric_limits<double>::infinity();
};

/** What the detections of a sequence hold, per class (after the threshold). */
struct TDetectionSummary
{
	struct TClass
	{
		size_t lines = 0, kept = 0, below_threshold = 0;
		size_t frames_with_detections = 0;  ///< frames with >= 1 kept detection
		size_t max_per_frame = 0;
		int max_frame = -1;             ///< a frame with max_per_frame detections (the first)
		std::vector<size_t> per_frame;  ///< kept detections per frame (size = frames)
	};
	std::map<std::string, TClass> classes;
	double min_score = -std::numeric_limits<double>::infinity();
	/** Written to the rawlog (detection_import.h, applyDetections): boxes, boxes dropped
	 * beyond max_range, frames with >= 1 box written. */
	size_t written = 0, beyond_range = 0, frames_written = 0;
	std::string toText() const;
};

/** Reads and checks the detections of `sequence` (DIR/CLASS/SSSS.txt for every class of the
 * options) and the calibration calibDir/SSSS.txt against a sequence of numFrames frames
 * (posesPath: named in the error). With `kept`: (*kept)[k] = the kept detections of frame k
 * (numFrames entries; classes in the order of the options, then file order). Throws
 * std::runtime_error (a missing folder or file, bad lines: file and line named) or
 * std::invalid_argument (bad options). */
TDetectionSummary readDetectionSet(const std::string& detectionsDir, const std::string& calibDir,
                                   const std::string& sequence, const TDetectionOptions& opts,
                                   size_t numFrames, const std::string& posesPath,
                                   std::vector<std::vector<TKittiDetection>>* kept = nullptr);
}  // namespace dynslam::kitti
