#pragma once
/** @file mrclam_files.h
 * Readers for the plain-text files of the UTIAS Multi-Robot Cooperative Localization and
 * Mapping dataset (Leung, Halpern, Barfoot, Liu, IJRR 30(8), 2011). Pure C++ (no MRPT).
 *
 * Every file: '#' comment lines (four header lines in the original files) and blank lines are
 * skipped, columns are separated by spaces/tabs, a trailing CR (CRLF files) is tolerated.
 * Bad input throws std::runtime_error("<path>:<line>: <what>"): a missing file, a wrong
 * number of columns, a token that is not a number (or not an integer where one is expected),
 * NaN/Inf, timestamps out of order (a time smaller than the previous one), a duplicate
 * barcode/subject. */
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace dynslam::mrclam
{
constexpr int kFirstRobot = 1;  ///< robots are subjects 1..5
constexpr int kLastRobot = 5;
constexpr int kFirstLandmark = 6;  ///< landmarks are subjects 6..20
constexpr int kLastLandmark = 20;
inline bool isRobotSubject(int s) { return s >= kFirstRobot && s <= kLastRobot; }
inline bool isLandmarkSubject(int s) { return s >= kFirstLandmark && s <= kLastLandmark; }

struct TOdometryRow
{
	double t, v, w;  ///< time [s], forward velocity [m/s], angular velocity [rad/s]
};
struct TMeasurementRow
{
	double t;  ///< [s]
	int barcode;
	double range, bearing;  ///< [m], [rad]
	int line;               ///< line number in the file (1-based), for messages
};
struct TPoseRow
{
	double t, x, y, theta;  ///< [s], [m], [m], [rad]
};

/** The files of one dataset folder that an import of one ego robot needs. */
struct TDataset
{
	std::string dir;
	std::map<int, int> barcodeToSubject;
	std::map<int, Eigen::Vector2d> landmarks;          ///< subject (6..20) -> Vicon position
	std::map<int, std::vector<TPoseRow>> groundTruth;  ///< robot subject -> Vicon poses
	int ego = 0;
	std::vector<TOdometryRow> odometry;         ///< of the ego robot
	std::vector<TMeasurementRow> measurements;  ///< of the ego robot, file order
};

/** A numeric table: rows of exactly `ncols` finite numbers, with their line numbers. */
struct TTable
{
	std::vector<std::vector<double>> rows;
	std::vector<int> lines;
};
/** Reads a table; `integerCols` lists columns that must hold integers; `timeCol` (>= 0) must
 * be non-decreasing. Throws std::runtime_error naming file and line. */
TTable readTable(const std::string& path, size_t ncols, const std::vector<size_t>& integerCols = {},
                 int timeCol = -1);

std::map<int, int> readBarcodes(const std::string& path);  ///< barcode -> subject
std::map<int, Eigen::Vector2d> readLandmarks(const std::string& path);
std::vector<TOdometryRow> readOdometry(const std::string& path);
std::vector<TMeasurementRow> readMeasurements(const std::string& path);
std::vector<TPoseRow> readGroundTruthPoses(const std::string& path);

/** File name of robot `robot`'s file of `kind` ("Odometry", "Measurement", "Groundtruth"). */
std::string robotFile(const std::string& dir, int robot, const std::string& kind);

/** Reads Barcodes.dat, Landmark_Groundtruth.dat, the ego's Odometry/Measurement/Groundtruth
 * and the Groundtruth of every other robot 1..5. All files are required. */
TDataset loadDataset(const std::string& dir, int egoRobot);
}  // namespace dynslam::mrclam
