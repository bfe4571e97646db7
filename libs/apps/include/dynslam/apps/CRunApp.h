#pragma once
/** @file CRunApp.h
 * The dynslam-run application (MRPT's KFSLAMApp pattern: the main() only calls initialize()
 * and run(), tests drive the class and read its result members).
 *
 *   dynslam-run -c config/run_highway.ini [-r file.rawlog] [--gt DIR/BASE | --no-gt]
 *               [-o OUTDIR] [--backend ekf] [--no-figures] [-q] [--full-covariance]
 *               [--scene FILE.3Dscene] [--video FILE.mp4]
 *
 * Runs one back-end (default: the dynamic EKF) over a rawlog and writes into OUTDIR:
 * ego.csv (per-step estimate, 3-sigma, ground truth, error, NEES, NIS), trajectory.tum,
 * landmarks.csv, object_features.csv, object_poses.csv, metrics.csv / metrics.txt and
 * consistency.txt (with ground truth), nees_ego.csv, nis.csv, figures (map.png,
 * ego_errors.png, nees_ego.png, nis.png) and effective_config.ini (the INI as used, followed by
 * the dump of every options struct). See doc/apps.md for the [Run] keys. */
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/COutputLogger.h>

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace dynslam::apps
{
class CRunApp : public mrpt::system::COutputLogger
{
public:
	CRunApp();
	/** Parses the command line, loads the INI and checks the back-end options. Returns false
	 * if nothing is to be run (--help, --version). Throws on bad arguments or INI values. */
	bool initialize(int argc, const char** argv);
	/** Loads the data, runs the back-end, evaluates and writes the outputs. Throws on errors. */
	void run();

	// --- settings (filled by initialize(); may be edited before run()) ---
	mrpt::config::CConfigFileMemory params;  ///< the INI (noise overrides are written into it)
	std::string iniFile;
	std::string rawlogFile;    ///< [Run] rawlog or -r
	std::string groundTruth;   ///< "DIR/BASE", "auto" (beside the rawlog) or empty (none)
	std::string scenarioFile;  ///< [Run] scenario ("auto": beside the rawlog)
	TDataSettings::ScenarioNoise noiseFromScenario = TDataSettings::ScenarioNoise::Off;
	std::string backend = "ekf";
	std::string outDir = "dynslam-run-out";
	bool figures = true;
	int progressEvery = 0;        ///< log every N steps (0: 10 times per run)
	bool fullCovariance = false;  ///< --full-covariance: OUTDIR/covariance.txt
	std::string sceneFile;        ///< --scene FILE.3Dscene (empty: none)
	std::string videoFile;        ///< --video FILE.mp4 (empty: none)

	// --- results of run() ---
	TFilterRun result;
	bool hasGroundTruth = false;
	io::TGroundTruth gt;
	std::optional<TEvaluation> evaluation;
	std::string groundTruthUsed, scenarioNoiseUsed;
	std::vector<std::string> writtenFiles;

private:
	/** What the command line overrides in the INI's [Run] section. */
	struct TRunOverrides
	{
		std::optional<std::string> rawlog, gt, backend, out;
		bool noGt = false, noFigures = false, strict = false;
	};
	/** Reads [Run] and checks the back-end's options, with the command line's overrides. */
	void readSettings(const TRunOverrides& o);
	/** --full-covariance, --scene, --video. */
	void writeOptionalOutputs(const TRawlog& rawlog);
	/** Writes OUTDIR/name with w and records it in writtenFiles. */
	void writeOutput(const std::string& name, const std::function<void(std::ostream&)>& w);
	/** With ground truth: evaluation, metrics.csv/.txt, nees_ego.csv and the printed table;
	 * without: the NIS only. Then nis.csv. Returns the consistency summary. */
	eval::TConsistencySummary evaluateAndReport();
	/** map.png; with ground truth ego_errors.png and nees_ego.png; nis.png. */
	void drawFigures(const eval::TConsistencySummary& summary);
};
}  // namespace dynslam::apps
