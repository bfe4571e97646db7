#pragma once
/** @file CMonteCarloApp.h
 * The dynslam-montecarlo application: the paper's experiment (Section V, Table I). For each
 * noise level of eq. (5)-(7) (w1v1 .. w3v3) and each run, the scenario is simulated in memory
 * with its own noise seed (libs/sim, no file IO), the back-end (default: the dynamic EKF,
 * configured with that level's Sigma_v and Sigma_0 = Sigma_w) runs on it, and the run is scored
 * against the ground truth. Runs are independent seeded jobs spread over worker threads; the
 * results do not depend on the number of threads.
 *
 *   dynslam-montecarlo [-c config/montecarlo.ini] [--runs N] [--levels w1v1,w2v2|all]
 *                      [--threads T] [--seed S] [--out DIR] [--no-figures] [-q]
 *                      [--shard i/n]            run only part i of n of the (level, run) grid
 *   dynslam-montecarlo --merge DIR... --out DIR  tables from the shards' per-run records
 *
 * Prints Table I (ours / paper per cell) and the NEES summary per level; with --out DIR writes
 * table1.md, table1.csv (one row per level and quantity, ours and the paper's), nees_summary.csv
 * and .md, runs.csv (every run's metrics and seed), nees_ego_<level>.png/.csv and
 * effective_config.ini. Noise seed of run r at level L: seed + 1000 * (index of L in
 * w1v1..w3v3) + r, so a run's result does not depend on which levels are selected either. */
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/eval/table1.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/COutputLogger.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dynslam::apps
{
class CMonteCarloApp : public mrpt::system::COutputLogger
{
public:
	CMonteCarloApp();
	/** Parses the command line and loads the INI and the scenario. Returns false for --help /
	 * --version. Throws on bad arguments or INI values. */
	bool initialize(int argc, const char** argv);
	/** Runs the sweep, prints the tables and (with an output dir) writes the files. */
	void run();

	/** "i/n" of --shard as (i, n); throws std::invalid_argument unless 1 <= i <= n. */
	static std::pair<int, int> parseShard(const std::string& v);
	/** The noise seed of run `run` at paper level `level` (w1v1..w3v3). */
	uint64_t runSeed(const std::string& level, int run) const;

	// --- settings (filled by initialize(); may be edited before run()) ---
	mrpt::config::CConfigFileMemory params;
	std::string iniFile, scenarioFile;
	sim::TScenarioOptions scenario;
	std::string backend = "ekf";
	int runs = 25;
	std::vector<std::string> levels;  ///< default: all 9
	int threads = 0;                  ///< 0: std::thread::hardware_concurrency()
	uint64_t seed = 1;
	std::string outDir;  ///< empty: print only
	bool figures = true, progress = true;
	/** [MonteCarlo] initial_covariance: sigma_w (the paper: Sigma_0 = Sigma_w of the level) or
	 * ini ([DynamicKFSLAM] Sigma_0 as written, e.g. 0 for a filter anchored at the true start). */
	bool sigma0FromLevel = true;
	/** --shard i/n (1 <= i <= n): only the jobs j (level-major index in the whole grid) with
	 * j mod n = i - 1, same seeds as the whole sweep; writes shard_<i>_of_<n>.runs (per-run
	 * records, dynslam/eval/run_records.h) and runs.csv, no tables. 0/0: not sharded. */
	int shardIndex = 0, shardCount = 0;
	/** --merge: folders with *.runs files of one sweep; run() then merges instead of running. */
	std::vector<std::string> mergeDirs;

	// --- results of run() ---
	struct TRunResult
	{
		std::string level;
		int run = 0;
		uint64_t seed = 0;
		eval::TRunMetrics metrics;
		eval::TRunConsistency consistency;
		size_t steps = 0;
	};
	std::vector<TRunResult> results;       ///< level-major, then run (a shard: its runs only)
	std::vector<std::string> mergedFiles;  ///< --merge: the record files read
	eval::TTable1 table;
	std::vector<std::pair<std::string, eval::TConsistencySummary>> nees;  ///< per level
	double wallSeconds = 0;    ///< the whole sweep (simulation + filtering + scoring)
	double meanMsPerStep = 0;  ///< filter time per step, mean over runs
	int threadsUsed = 0;
	std::vector<std::string> writtenFiles;

private:
	void writeOutputs();
	/** Table I and the NEES summary from `results` (every run of every level). */
	void aggregate();
	void printTables() const;
	void writeShard();  ///< --shard: the record file and runs.csv
	void runMerge();    ///< --merge
	void writeRunsCsv(std::ostream& os) const;
};

/** The NEES summary per level as a Markdown table (ego, static map, landmarks, object poses,
 * NIS: ANEES with its two-sided 95% bounds and the share of steps inside their bounds). */
void writeNeesMarkdown(std::ostream& os,
                       const std::vector<std::pair<std::string, eval::TConsistencySummary>>& nees);
}  // namespace dynslam::apps
