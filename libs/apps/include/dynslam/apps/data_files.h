#pragma once
/** @file data_files.h
 * Input files of the apps besides the rawlog: locating the shipped defaults, resolving paths
 * written in INI files, loading the ground truth of a rawlog (with the step-count check) and
 * the noise levels of a simulated scenario (<base>_scenario.ini written by dynslam-simulate).
 * See doc/apps.md. */
#include <dynslam/io/ground_truth.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace dynslam::apps
{
/** A shipped file (e.g. "datasets/highway.rawlog" or "config/compare_highway.ini"), searched
 * in this order: the current directory, <exe dir>/../share/dynslam (an install), the source
 * tree (compile-time DYNSLAM_SOURCE_DIR). Returns the first existing path; throws
 * std::runtime_error listing every place tried. */
std::string locateShippedFile(const std::string& relPath);
/** The places locateShippedFile() tries, in order. */
std::vector<std::string> shippedFileCandidates(const std::string& relPath);

/** p itself if empty or absolute; otherwise baseDir/p (INI paths are relative to the INI
 * file's folder). */
std::string resolvePath(const std::string& p, const std::string& baseDir);
/** Folder of a file path ("." if none). */
std::string folderOf(const std::string& path);

/** Ground-truth files: D/B_gt_ego.csv etc. (ground_truth.h). A spec is "D/B"; a path to one of
 * the files ("D/B_gt_ego.csv") is accepted too. */
struct TGroundTruthSpec
{
	std::string dir, base;
	std::string str() const;  ///< "D/B"
};
TGroundTruthSpec parseGroundTruthSpec(const std::string& spec);
/** "D/B" for rawlog D/B.rawlog if D/B_gt_ego.csv exists; else MRPT's simul-landmarks robot
 * path "D/B.rawlog_ground_truth_robot_path.txt" if it exists; else an empty string. */
std::string groundTruthBesideRawlog(const std::string& rawlogPath);

/** True if the spec names a robot-path file in MRPT's format (ground_truth.h,
 * io::readMrptGroundTruth): "..._ground_truth_robot_path.txt" (simul-landmarks) or
 * "..._gt_robot_path.txt" (dynslam-simulate's kf-slam files). */
bool isMrptGroundTruthSpec(const std::string& spec);
/** The landmarks file beside such a robot-path file: "..._ground_truth.txt" or
 * "..._gt_landmarks.txt". */
std::string mrptLandmarksFileFor(const std::string& robotPathFile);

/** Reads the ground truth and checks that it has one step per rawlog pair. Throws
 * std::runtime_error naming the files on a missing/malformed file or a step-count mismatch. */
io::TGroundTruth loadGroundTruthFor(const std::string& spec, size_t rawlogSteps,
                                    const std::string& rawlogPath);

/** Noise of a simulated scenario ([Noise] section of <base>_scenario.ini). */
struct TScenarioNoise
{
	std::string file, level;
	Eigen::Matrix3d Sigma_w = Eigen::Matrix3d::Zero(), Sigma_0 = Eigen::Matrix3d::Zero();
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Zero();
	/** The stds that MRPT's range-bearing filter gets: std_range = sqrt(sigma_v) and the yaw
	 * std at the scenario's typical range (dynslam-simulate computes both). */
	double std_range = 0, std_yaw_deg = 0;
};
/** Reads the [Noise] section (keys level, sigma_w, sigma_v, sigma_0, std_range, std_yaw_deg).
 * Throws std::runtime_error naming the file and key. */
TScenarioNoise readScenarioNoise(const std::string& path);
/** "D/B_scenario.ini" for rawlog D/B.rawlog (whether or not it exists). */
std::string scenarioBesideRawlog(const std::string& rawlogPath);
/** The landmark gaps ([Scenario] landmark_gaps, metres along x) of a highway scenario file;
 * empty if the file does not exist, has no such key or is not a highway (issue 13). A file
 * with the key is read with sim::loadScenario (its errors propagate). */
std::vector<std::pair<double, double>> highwayLandmarkGaps(const std::string& scenarioPath);

/** Writes the scenario noise into the filter sections of an in-memory INI, so that the
 * filters use the noise the data was made with:
 *  - [dynSection] Sigma_v (cartesian model: sigma_v; range_bearing: diag(std_range^2,
 *    std_yaw^2)), Sigma_0 = sigma_0, and Sigma_w when motion_noise = config;
 *  - [staticSection] std_sensor_range, std_sensor_yaw_deg (MRPT's CRangeBearingKFSLAM2D).
 * Empty section names are skipped. Returns a one-line description of what was set. */
std::string applyScenarioNoise(mrpt::config::CConfigFileMemory& ini, const TScenarioNoise& n,
                               const std::string& dynSection, const std::string& staticSection);
}  // namespace dynslam::apps
