#include <dynslam/apps/CMonteCarloApp.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/mrpt_sections.h>
#include <dynslam/apps/progress.h>
#include <dynslam/apps/run_outputs.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/sim/scenario.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>
#include <tuple>

#include "cmdline.h"

namespace dynslam::apps
{
namespace
{
const char* kMonteCarloSection = "MonteCarlo";

std::vector<std::string> parseLevels(const std::string& s)
{
	std::vector<std::string> out = splitList(s);
	for (auto& item : out)
		for (char& c : item) c = char(std::tolower(static_cast<unsigned char>(c)));
	if (out.size() == 1 && out[0] == "all") return eval::paperNoiseLevels();
	const auto& known = eval::paperNoiseLevels();
	for (const auto& l : out)
		if (std::find(known.begin(), known.end(), l) == known.end())
			throw std::invalid_argument("unknown noise level '" + l +
			                            "' (known: w1v1..w3v3 or all)");
	if (out.empty()) throw std::invalid_argument("empty list of noise levels");
	return out;
}

int levelIndex(const std::string& level)
{
	const auto& k = eval::paperNoiseLevels();
	return int(std::find(k.begin(), k.end(), level) - k.begin());
}
}  // namespace

CMonteCarloApp::CMonteCarloApp() : mrpt::system::COutputLogger("dynslam-montecarlo")
{
	levels = eval::paperNoiseLevels();
}

uint64_t CMonteCarloApp::runSeed(const std::string& level, int r) const
{
	return seed + 1000u * uint64_t(levelIndex(level)) + uint64_t(r);
}

namespace
{
/** The [MonteCarlo] settings of app.params (after the scenario file): each INI value unless
 * its command-line option is set; then the MRPT sections' check (warnings, errors with
 * `strict`) and the back-end's options (fail early on bad options). */
void readMonteCarloSettings(CMonteCarloApp& app, TCLAP::ValueArg<int>& argRuns,
                            TCLAP::ValueArg<std::string>& argLevels,
                            TCLAP::ValueArg<int>& argThreads, TCLAP::ValueArg<long long>& argSeed,
                            TCLAP::SwitchArg& argNoFig, bool strict)
{
	using namespace dynslam::config;
	auto& params = app.params;
	rejectUnknownKeys(params, kMonteCarloSection,
	                  {"scenario", "backend", "runs", "levels", "threads", "seed", "figures",
	                   "initial_covariance"});
	app.scenarioFile =
	    resolvePath(requireString(params, kMonteCarloSection, "scenario"), folderOf(app.iniFile));
	app.scenario = sim::loadScenario(app.scenarioFile);
	app.backend = readString(params, kMonteCarloSection, "backend", "ekf");
	int& runs = app.runs;
	runs = int(readInt(params, kMonteCarloSection, "runs", 25));
	if (argRuns.isSet()) runs = argRuns.getValue();
	if (runs < 1) fail(kMonteCarloSection, "runs", std::to_string(runs), "must be >= 1");
	const std::string lv = !argLevels.getValue().empty()
	                           ? argLevels.getValue()  // --noise (or --levels)
	                           : readString(params, kMonteCarloSection, "levels", "all");
	try
	{
		app.levels = parseLevels(lv);
	}
	catch (const std::invalid_argument& e)
	{
		fail(kMonteCarloSection, "levels", lv, e.what());
	}
	int& threads = app.threads;
	threads = int(readInt(params, kMonteCarloSection, "threads", 0));
	if (argThreads.isSet()) threads = argThreads.getValue();
	if (threads < 0) fail(kMonteCarloSection, "threads", std::to_string(threads), "must be >= 0");
	const long long s =
	    argSeed.isSet() ? argSeed.getValue() : readInt(params, kMonteCarloSection, "seed", 1);
	if (s < 0 || s + 1000LL * 9 + runs > 4294967295LL)
		fail(kMonteCarloSection, "seed", std::to_string(s),
		     "seed + 1000 * 8 + runs must be in [0, 4294967295]");
	app.seed = uint64_t(s);
	app.figures = readBool(params, kMonteCarloSection, "figures", true) && !argNoFig.getValue();
	app.sigma0FromLevel =
	    readChoice(params, kMonteCarloSection, "initial_covariance", {"sigma_w", "ini"}, 0) == 0;
	for (const auto& w : checkMrptSections(params, app.iniFile, strict))
		app.logStr(mrpt::system::LVL_WARN, w);
	makeBackend(app.backend, params);
}

/** Runs f; a std::invalid_argument (an INI error) is rethrown naming the INI file. */
template <typename F>
void namingTheIniFile(const std::string& iniFile, F&& f)
{
	try
	{
		f();
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument(inConfigFile(iniFile, e.what()));
	}
}

/** One noise level of the sweep: scenario options with the level's noise, ground truth and
 * the filter INI text. */
struct TLevelSetup
{
	sim::TScenarioOptions opt;
	io::TGroundTruth gt;
	std::string ini;
};

TLevelSetup levelSetup(const CMonteCarloApp& app, const std::string& level, bool isStatic)
{
	TLevelSetup L;
	L.opt = app.scenario;
	L.opt.setNoiseLevel(level);
	// The paper: Sigma_0 = Sigma_w; initial_covariance = ini keeps the INI's Sigma_0.
	L.opt.Sigma_0 =
	    app.sigma0FromLevel
	        ? L.opt.Sigma_w
	        : Eigen::Matrix3d(config::readCovariance(app.params, "DynamicKFSLAM", "Sigma_0",
	                                                 Eigen::Matrix3d::Zero(), 3, false, true));
	L.gt = sim::buildGroundTruth(L.opt);
	TScenarioNoise n;
	n.file = "noise level " + level;
	n.level = level;
	n.Sigma_w = L.opt.Sigma_w;
	n.Sigma_v = L.opt.Sigma_v;
	n.Sigma_0 = L.opt.Sigma_0;
	n.std_range = L.opt.std_range;
	n.std_yaw_deg = L.opt.std_yaw * 180.0 / M_PI;
	mrpt::config::CConfigFileMemory ini(app.params.getContent());
	applyScenarioNoise(ini, n, isStatic ? "" : "DynamicKFSLAM",
	                   isStatic ? "RangeBearingKFSLAM" : "");
	L.ini = ini.getContent();
	return L;
}

/** Simulates and filters one run of a level; res.seed is set. */
void simulateAndFilter(const std::string& backend, const TLevelSetup& L,
                       CMonteCarloApp::TRunResult& res)
{
	const sim::TSimulatedRun simRun = sim::simulateMeasurements(L.gt, L.opt, res.seed);
	mrpt::config::CConfigFileMemory ini(L.ini);
	auto filter = makeBackend(backend, ini);
	if (auto* lg = dynamic_cast<mrpt::system::COutputLogger*>(filter.get()))
		lg->setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const TFilterRun fr = runFilter(*filter, simRun.actions, simRun.frames);
	res.steps = fr.steps;
	res.metrics = eval::computeRunMetrics(L.gt, fr.est);
	res.consistency = eval::computeRunConsistency(L.gt, fr.est);
}

/** The exception being handled (call inside a catch), as a std::runtime_error naming the run. */
std::exception_ptr runError(const std::string& level, int r)
{
	std::ostringstream what;
	try
	{
		throw;
	}
	catch (const std::exception& e)
	{
		what << "level " << level << " run " << r << ": " << e.what();
	}
	catch (...)
	{
		what << "level " << level << " run " << r << ": unknown error";
	}
	return std::make_exception_ptr(std::runtime_error(what.str()));
}

/** Runs the jobs (indices into the level-major grid of app.results) on app.threadsUsed
 * threads; rethrows the first failure. */
void runJobs(CMonteCarloApp& app, const std::vector<TLevelSetup>& lv,
             const std::vector<size_t>& jobs)
{
	const size_t total = jobs.size();
	const int runs = app.runs;
	std::atomic<size_t> next{0};
	std::atomic<bool> failed{false};
	std::exception_ptr error;
	std::mutex errMtx;
	CProgressBar bar("runs", total, std::cerr, app.progress);
	auto worker = [&]()
	{
		for (;;)
		{
			const size_t idx = next.fetch_add(1);
			if (idx >= total || failed) return;
			const size_t j = jobs[idx];
			const size_t li = j / size_t(runs);
			const int r = int(j % size_t(runs));
			try
			{
				CMonteCarloApp::TRunResult& res = app.results[j];
				res.level = app.levels[li];
				res.run = r;
				res.seed = app.runSeed(app.levels[li], r);
				simulateAndFilter(app.backend, lv[li], res);
			}
			catch (...)
			{
				std::lock_guard<std::mutex> lk(errMtx);
				if (!error) error = runError(app.levels[li], r);
				failed = true;
				return;
			}
			bar.advance();
		}
	};
	std::vector<std::thread> pool;
	for (int t = 0; t < app.threadsUsed; ++t) pool.emplace_back(worker);
	for (auto& t : pool) t.join();
	bar.finish();
	if (error) std::rethrow_exception(error);
}
}  // namespace

namespace
{
/** --levels, the old spelling of --noise: its value goes to --noise; both is an error. */
void takeOldSpelling(TCLAP::ValueArg<std::string>& noise, TCLAP::ValueArg<std::string>& levels)
{
	if (levels.isSet() && noise.isSet())
		throw std::invalid_argument("give --noise or --levels (its old spelling), not both");
	if (levels.isSet()) noise.getValue() = levels.getValue();
}
}  // namespace

bool CMonteCarloApp::initialize(int argc, const char** argv)
{
	TCLAP::CmdLine cmd(
	    "dynslam-montecarlo: the Monte Carlo experiment of the paper (Table I): noise levels x "
	    "runs of the highway scenario, simulated in memory, on all cores. See doc/apps.md.",
	    ' ', "0.1");
	TCLAP::ValueArg<std::string> argIni(
	    "c", "config",
	    "INI file ([MonteCarlo] and the back-end's sections); default config/montecarlo.ini", false,
	    "", "file.ini", cmd);
	TCLAP::ValueArg<int> argRuns("", "runs", "Runs per noise level ([MonteCarlo] runs)", false, 0,
	                             "N", cmd);
	TCLAP::ValueArg<std::string> argLevels(
	    "", "noise", "Noise levels w1v1..w3v3, comma-separated, or all ([MonteCarlo] levels)",
	    false, "", "list", cmd);
	TCLAP::ValueArg<std::string> argLevelsOld("", "levels", "Deprecated spelling of --noise", false,
	                                          "", "list", cmd);
	TCLAP::ValueArg<int> argThreads(
	    "", "threads", "Worker threads (0: all cores) ([MonteCarlo] threads)", false, -1, "T", cmd);
	TCLAP::ValueArg<long long> argSeed("", "seed", "Base noise seed ([MonteCarlo] seed)", false, -1,
	                                   "S", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "o", "out", "Write table1.md/.csv, NEES summaries, runs.csv and figures here", false, "",
	    "dir", cmd);
	TCLAP::SwitchArg argNoFig("", "no-figures", "Do not draw the NEES figures", cmd);
	TCLAP::SwitchArg argQuiet("q", "quiet", "No progress bar; only the tables", cmd);
	TCLAP::ValueArg<std::string> argShard(
	    "", "shard",
	    "Run only part i of n (1 <= i <= n) of the (level, run) grid, with the seeds of the whole "
	    "sweep; writes per-run records into --out for --merge",
	    false, "", "i/n", cmd);
	TCLAP::SwitchArg argMerge(
	    "", "merge", "Build the tables from the *.runs files of the given shard folders", cmd);
	TCLAP::UnlabeledMultiArg<std::string> argDirs("dirs", "Shard folders (with --merge)", false,
	                                              "DIR", cmd);
	TCLAP::SwitchArg argStrict("", "strict",
	                           "Unknown keys in MRPT's own INI sections ([RangeBearingKFSLAM], "
	                           "[*_KalmanFilter]) are errors, not warnings",
	                           cmd);
	if (!detail::parseCommandLine(cmd, argc, argv, "dynslam-montecarlo")) return false;
	takeOldSpelling(argLevels, argLevelsOld);
	progress = !argQuiet.getValue();
	if (argQuiet.getValue()) setMinLoggingLevel(mrpt::system::LVL_WARN);
	// The folder list takes any word, so an unknown option lands there.
	for (const auto& d : argDirs.getValue())
		if (!d.empty() && d[0] == '-')
			throw std::invalid_argument("bad command line: unknown option '" + d +
			                            "' (see dynslam-montecarlo --help)");
	if (argMerge.getValue())
	{
		mergeDirs = argDirs.getValue();
		if (mergeDirs.empty())
			throw std::invalid_argument("--merge needs at least one shard folder");
		if (argShard.isSet()) throw std::invalid_argument("--merge and --shard exclude each other");
		outDir = argOut.getValue();
		figures = !argNoFig.getValue();
		return true;
	}
	if (!argDirs.getValue().empty())
		throw std::invalid_argument("unexpected argument '" + argDirs.getValue().front() +
		                            "' (folders are only given with --merge)");
	if (argShard.isSet())
	{
		std::tie(shardIndex, shardCount) = parseShard(argShard.getValue());
		if (argOut.getValue().empty())
			throw std::invalid_argument("--shard needs --out DIR (the per-run records go there)");
	}

	iniFile = argIni.isSet() ? argIni.getValue() : locateShippedFile("config/montecarlo.ini");
	loadIniFile(iniFile, params);
	outDir = argOut.getValue();
	namingTheIniFile(iniFile,
	                 [&]
	                 {
		                 readMonteCarloSettings(*this, argRuns, argLevels, argThreads, argSeed,
		                                        argNoFig, argStrict.getValue());
	                 });
	if (!outDir.empty()) checkOutputDirUsable(outDir);  // created when the results are written
	return true;
}

void CMonteCarloApp::run()
{
	if (!mergeDirs.empty())
	{
		runMerge();
		return;
	}
	using Clock = std::chrono::steady_clock;
	const auto t0 = Clock::now();
	results.clear();
	nees.clear();
	table = eval::TTable1();
	writtenFiles.clear();
	const bool isStatic = backend == "static_all" || backend == "static_landmarks_only";

	std::vector<TLevelSetup> lv;
	for (const auto& level : levels) lv.push_back(levelSetup(*this, level, isStatic));

	const size_t grid = levels.size() * size_t(runs);
	// The jobs of this process: the whole grid, or every shardCount-th job of it.
	std::vector<size_t> jobs;
	for (size_t j = 0; j < grid; ++j)
		if (shardCount == 0 || j % size_t(shardCount) == size_t(shardIndex - 1)) jobs.push_back(j);
	const size_t total = jobs.size();
	results.assign(grid, TRunResult());
	threadsUsed = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
	threadsUsed = int(std::max<size_t>(1, std::min<size_t>(size_t(threadsUsed), total)));
	MRPT_LOG_INFO_STREAM(levels.size()
	                     << " noise level(s) x " << runs << " runs = " << grid << " runs of '"
	                     << backend << "'"
	                     << (shardCount ? ", shard " + std::to_string(shardIndex) + "/" +
	                                          std::to_string(shardCount) + ": " +
	                                          std::to_string(total) + " runs"
	                                    : std::string())
	                     << " on " << threadsUsed << " thread(s); scenario " << scenarioFile);

	runJobs(*this, lv, jobs);

	if (shardCount > 0)
	{
		std::vector<TRunResult> mine;
		for (size_t j : jobs) mine.push_back(results[j]);
		results = std::move(mine);
	}
	meanMsPerStep = 0;
	for (const auto& r : results) meanMsPerStep += r.metrics.ms_per_step / double(results.size());
	wallSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
	if (shardCount > 0)
	{
		writeShard();
		return;
	}
	aggregate();
	printTables();
	char buf[200];
	std::snprintf(buf, sizeof(buf),
	              "\n%zu runs (%zu levels x %d) on %d thread(s): wall time %.2f s; filter %.3f "
	              "ms/step, %.1f ms/run\n",
	              total, levels.size(), runs, threadsUsed, wallSeconds, meanMsPerStep,
	              meanMsPerStep * double(results.empty() ? 0 : results.front().steps));
	std::cout << buf << std::flush;
	if (!outDir.empty()) writeOutputs();
}

void CMonteCarloApp::aggregate()
{
	table = eval::TTable1();
	nees.clear();
	for (size_t li = 0; li < levels.size(); ++li)
	{
		std::vector<eval::TRunMetrics> m;
		std::vector<eval::TRunConsistency> c;
		for (int r = 0; r < runs; ++r)
		{
			m.push_back(results[li * size_t(runs) + size_t(r)].metrics);
			c.push_back(results[li * size_t(runs) + size_t(r)].consistency);
		}
		table.levels.push_back(eval::aggregateTable1Level(levels[li], m));
		nees.emplace_back(levels[li], eval::summarizeConsistency(c));
	}
}

void CMonteCarloApp::printTables() const
{
	std::cout << "\nTable I: RMSE averaged over " << runs << " run(s) per level, ours / paper\n\n";
	eval::writeTable1Markdown(std::cout, table);
	std::cout << "\nNEES / NIS per level (average over runs, two-sided 95% chi-square bounds)\n\n";
	writeNeesMarkdown(std::cout, nees);
}
}  // namespace dynslam::apps
