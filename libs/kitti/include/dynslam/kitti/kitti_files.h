#pragma once
/** @file kitti_files.h
 * Readers of the KITTI tracking files used by the importer (pure C++/Eigen, no MRPT):
 *  - poses/SSSS.txt: one line per frame (frame k = line k, 0-based), the 3x4 camera-to-world
 *    matrix [R t] row-major (12 numbers). Frame 0 is the identity in the files we use.
 *  - label_02/SSSS.txt: one line per annotated object per frame, 17 space-separated columns
 *    `frame track_id type truncated occluded alpha left top right bottom h w l x y z
 * rotation_y`.
 * Every malformed line throws std::runtime_error "FILE:LINE: what" (wrong column count, a
 * token that is not a number, NaN/Inf, a negative frame, a track ID < 0 on a box that is not
 * DontCare, a (frame, track) pair given twice, a rotation that is not one).
 * DontCare lines and boxes without 3-D data (dimensions <= 0 or the -1000 placeholders) are
 * skipped and counted, not errors. Every type is accepted (the importer never decides from the
 * type): the KITTI types (isKnownType) and any other word, which is counted per type
 * (TKittiLabels::unknown_types) and reported in the import summary. */
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace dynslam::kitti
{
using TCameraPose = Eigen::Matrix<double, 3, 4>;  ///< camera-to-world [R t]

/** One annotated 3-D box (a label line that is neither DontCare nor without 3-D data). */
struct TKittiBox
{
	int frame = 0;
	int track = 0;
	std::string type;
	double h = 0, w = 0, l = 0;  ///< height, width, length [m]
	double x = 0, y = 0, z = 0;  ///< centre of the bottom face, camera frame [m]
	double ry = 0;               ///< yaw about the camera y axis [rad]
	int line = 0;                ///< line in the label file
};

struct TKittiLabels
{
	std::string file;
	std::vector<TKittiBox> boxes;  ///< in file order
	size_t rows = 0;               ///< non-empty lines
	size_t dontcare = 0;           ///< DontCare lines (skipped)
	size_t no3d = 0;               ///< boxes without 3-D data (skipped)
	int max_frame = -1;            ///< largest frame index on any line (DontCare included)
	int max_frame_line = 0;        ///< the line where it occurs
	/** Label lines per type, DontCare excluded (boxes without 3-D data included). */
	std::map<std::string, size_t> types;
	/** Lines per type that is not a KITTI type (e.g. a typo, or a type of another data set). */
	std::map<std::string, size_t> unknown_types;
};

/** The types of KITTI's tracking and object labels: Car, Van, Truck, Pedestrian, Person (the
 * tracking labels' sitting person), Person_sitting (the object labels' name), Cyclist, Tram,
 * Misc, DontCare. */
bool isKnownType(const std::string& type);

/** "SSSS": exactly four digits, else std::invalid_argument. */
void checkSequenceName(const std::string& seq);
/** DIR/SSSS.txt */
std::string sequenceFile(const std::string& dir, const std::string& seq);

/** Reads a pose file. Throws std::runtime_error naming file and line. */
std::vector<TCameraPose> readPoses(const std::string& path);
/** Reads a label file. Throws std::runtime_error naming file and line. */
TKittiLabels readLabels(const std::string& path);
/** Throws std::runtime_error if a label refers to a frame with no pose (names both files and
 * the label line). */
void checkLabelsAgainstPoses(const TKittiLabels& labels, size_t numPoses,
                             const std::string& posesPath);
}  // namespace dynslam::kitti
