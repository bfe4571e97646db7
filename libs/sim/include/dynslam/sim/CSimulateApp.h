#pragma once
/** @file CSimulateApp.h
 * The dynslam-simulate application (MRPT's KFSLAMApp pattern: the main() only calls
 * initialize() and run(), so tests can drive it).
 *
 * Usage: dynslam-simulate -c config/highway.ini [-o DIR] [--name BASE] [--noise w2v2]
 *        [--world-seed N] [--noise-seed N] [--steps N] [--figure out.png] [--figure-only]
 *        [--stream]
 *
 * Writes into DIR: BASE.rawlog, the five ground-truth files of ground_truth.h, the kf-slam
 * files (BASE_gt_landmarks.txt, BASE_gt_robot_path.txt, BASE_gt_data_association.txt) and
 * BASE_scenario.ini (the effective configuration). */
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <mrpt/system/COutputLogger.h>

#include <string>
#include <vector>

namespace dynslam::sim
{
class CSimulateApp : public mrpt::system::COutputLogger
{
public:
	CSimulateApp();
	/** Parses the command line and loads the INI. Returns false if nothing is to be run
	 * (--help, --version). Throws std::invalid_argument on bad arguments or INI values. */
	bool initialize(int argc, const char** argv);
	/** Simulates and writes the files. Throws on errors. */
	void run();

	// Settings (filled by initialize(); may be edited before run()).
	TScenarioOptions options;
	std::string iniFile;
	std::string outDir = ".";
	std::string figureFile;  ///< empty: no figure
	bool figureOnly = false;
	bool stream = false;  ///< simulate straight into the rawlog (no DA file)

	// Results of run().
	io::TGroundTruth groundTruth;
	std::vector<std::string> writtenFiles;
	size_t numRawlogEntries = 0;  ///< ACT + SF entries (2 per step)
	size_t numMeasurements = 0;   ///< range-bearing readings in all SFs (0 with --stream)
};
}  // namespace dynslam::sim
