#pragma once
/** @file app_common.h
 * Pieces shared by the app classes: INI loading, evaluation of one run against the ground
 * truth, and the per-filter output files. */
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/common/app_support.h>
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <optional>
#include <string>
#include <vector>

namespace dynslam::apps
{
/** Loads an INI file into memory. Throws std::runtime_error naming the file if it is missing
 * or unreadable. */
void loadIniFile(const std::string& path, mrpt::config::CConfigFileMemory& out);

/** INI checks shared by the apps: [OdometryNoise] (rawlog_io.h; throws std::invalid_argument on
 * bad values) and unknown keys in MRPT's own sections (mrpt_sections.h: returned as warnings,
 * or thrown with strict). */
std::vector<std::string> checkSharedSections(const mrpt::config::CConfigFileBase& params,
                                             const std::string& iniFile, bool strict);

/** Splits a command-line list at commas, spaces and tabs, dropping empty items. */
std::vector<std::string> splitList(const std::string& s);

/** Metrics and consistency of one run (only with ground truth). */
struct TEvaluation
{
	eval::TRunMetrics metrics;
	eval::TRunConsistency consistency;
	eval::TConsistencySummary summary;  ///< the single-run summary (chi-square bounds of 1 run)
};
TEvaluation evaluateRun(const io::TGroundTruth& gt, const eval::TRunEstimates& est);

/** One time base everywhere: copies the rawlog's observation stamps into the ego estimates
 * (t of ego.csv and trajectory.tum), with or without ground truth. The simulator's and the
 * MRCLAM importer's ground truth carry the same stamps (BASE_gt_ego.tum), so evo associates
 * the two files. A step without a stamp keeps t = NaN (the writers then use gt.t). */
void setEgoTimes(TFilterRun& run);

/** Writes <dir>/<prefix>ego.csv, trajectory.tum, landmarks.csv, object_features.csv,
 * object_poses.csv (writers.h); appends the paths to `written`. */
void writeEstimateFiles(const std::string& dir, const std::string& prefix,
                        const eval::TRunEstimates& est, const io::TGroundTruth* gt,
                        std::vector<std::string>& written);

/** The data keys shared by [Run] and [Compare] (paths already resolved). */
struct TDataSettings
{
	std::string rawlog;
	std::string groundTruth;        ///< "DIR/BASE", "auto" (beside the rawlog, if there) or empty
	std::string scenario = "auto";  ///< scenario INI for the noise, "auto": beside the rawlog
	/** noise_from_scenario = false | true | auto: write the scenario's noise into the filter
	 * sections; auto: only if the scenario file exists (else the INI's values are used). */
	enum class ScenarioNoise
	{
		Off,
		On,
		Auto
	} noiseFromScenario = ScenarioNoise::Off;
	/** The INI is the app's shipped default (dynslam-compare without -c): without a scenario
	 * file its noise values do not count (noise_sources.h). */
	bool iniIsShippedDefault = false;
};
/** Reads rawlog, ground_truth, scenario and noise_from_scenario from [section]; paths are
 * resolved relative to iniDir. */
TDataSettings readDataSettings(const mrpt::config::CConfigFileBase& ini, const std::string& section,
                               const std::string& iniDir);

struct TLoadedData
{
	TRawlog rawlog;
	std::optional<io::TGroundTruth> gt;
	std::string groundTruthUsed;  ///< "DIR/BASE" or empty
	std::string noiseUsed;        ///< where the noise written into the INI came from, or empty
};
/** The ground truth of a loaded rawlog, checked against it: the project's CSVs (spec "DIR/BASE",
 * loadGroundTruthFor) or MRPT's text files (spec = the robot-path file, isMrptGroundTruthSpec:
 * path rows are matched to the rawlog's sensory frames by TRawlog::frameIndex, times are the
 * observations' timestamps). Throws std::runtime_error naming the files. */
io::TGroundTruth loadGroundTruthForRawlog(const std::string& spec, const TRawlog& rawlog);

/** Loads the rawlog (format #2 with the odometry noise of [OdometryNoise] in params), the ground
 * truth (checked against the rawlog) and, with noiseFromScenario, writes the scenario noise into
 * the filter sections of `params` (applyScenarioNoise). Throws std::runtime_error with clear
 * messages. */
TLoadedData loadData(const TDataSettings& s, mrpt::config::CConfigFileMemory& params,
                     const std::string& dynSection, const std::string& staticSection);

/** NIS samples of a run without ground truth (for the NIS figure). */
eval::TRunConsistency nisOnly(const eval::TRunEstimates& est);

/** dir/name as a string. */
std::string joinPath(const std::string& dir, const std::string& name);
}  // namespace dynslam::apps
