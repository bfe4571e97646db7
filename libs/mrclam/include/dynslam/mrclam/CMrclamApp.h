#pragma once
/** @file CMrclamApp.h
 * The dynslam-mrclam app (MRPT's KFSLAMApp pattern: a thin main() around this class).
 *
 *   dynslam-mrclam --dataset DIR --robot N --out DIR [--config INI] [--duration S] [--base B]
 *                  [--anonymous [--seed S]]
 *   dynslam-mrclam --dataset DIR --estimate-noise (--robot N | --all-robots [--leave-out N])
 *                  [--out DIR] [--config INI]
 *
 * Import: reads DIR (MRCLAM files), converts robot N (import.h) and writes into --out the
 * rawlog, the ground truth, `<B>_summary.txt` and `<B>_import.ini` (B defaults to robotN).
 * --estimate-noise: residual statistics against the ground truth (noise_estimation.h), per
 * robot and pooled; printed and, with --out, saved as `noise_estimate.txt`; with --out also
 * `noise_estimate.ini` (the pooled estimate as [MRCLAM_Import] keys, TNoiseEstimate::toIni).
 * --leave-out N: all robots but N (the leave-one-robot-out check). --anonymous: the IDs of
 * anonymous.h (seed --seed, default 1); every import also writes `<B>_gt_classes.csv`. */
#include <dynslam/mrclam/CMrclamOptions.h>
#include <dynslam/mrclam/import.h>
#include <dynslam/mrclam/noise_estimation.h>
#include <mrpt/system/COutputLogger.h>

#include <map>
#include <string>

namespace dynslam::mrclam
{
class CMrclamApp : public mrpt::system::COutputLogger
{
public:
	CMrclamApp();

	/** Parses the command line and loads the config. Returns false when the program should
	 * stop now (help or version shown: exit code 0). Throws std::invalid_argument on a bad
	 * command line, std::runtime_error / std::invalid_argument naming the file on a bad config. */
	bool initialize(int argc, const char** argv);

	/** Runs the import or the noise estimation. Throws std::runtime_error on bad input. */
	void run();

	// --- settings (filled by initialize(), or set directly by tests) ---
	std::string dataset_dir, out_dir, config_file, base;
	int robot = 0;
	bool estimate_noise = false, all_robots = false;
	int leave_out = 0;       ///< with all_robots: a robot 1..5 left out of the estimate (0: none)
	bool anonymous = false;  ///< import with anonymous IDs (anonymous.h)
	bool quiet = false;      ///< -q: no import summary on stdout, only warnings and errors
	uint32_t anonymous_seed = 1;  ///< the permutation's seed
	TMrclamOptions options;

	// --- results ---
	TImportSummary summary;  ///< of the import (last robot with --estimate-noise)
	std::map<int, TNoiseEstimate> noise_per_robot;
	TNoiseEstimate noise_pooled;
	std::map<int, double> delay_per_robot;  ///< best odometry delay per robot [s]
	double delay_pooled = 0;                ///< best odometry delay, all robots pooled [s]

private:
	void runImport();
	void runNoiseEstimation();
};
}  // namespace dynslam::mrclam
