// dynslam-montecarlo --shard i/n and --merge DIR... (CMonteCarloApp; doc/apps.md).
#include <dynslam/apps/CMonteCarloApp.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/run_outputs.h>
#include <dynslam/eval/run_records.h>
#include <dynslam/eval/writers.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
std::string joined(const std::vector<std::string>& v)
{
	std::string s;
	for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
	return s;
}
}  // namespace

std::pair<int, int> CMonteCarloApp::parseShard(const std::string& v)
{
	const auto slash = v.find('/');
	int i = 0, n = 0;
	try
	{
		size_t p1 = 0, p2 = 0;
		if (slash == std::string::npos) throw std::invalid_argument(v);
		i = std::stoi(v.substr(0, slash), &p1);
		n = std::stoi(v.substr(slash + 1), &p2);
		if (p1 != slash || p2 != v.size() - slash - 1) throw std::invalid_argument(v);
	}
	catch (const std::exception&)
	{
		throw std::invalid_argument("--shard '" + v + "': expected i/n, e.g. 2/8");
	}
	if (n < 1 || i < 1 || i > n)
		throw std::invalid_argument("--shard '" + v + "': need 1 <= i <= n");
	return {i, n};
}

void CMonteCarloApp::writeRunsCsv(std::ostream& os) const
{
	os << "level,run,seed,steps,ego_rmse_x,ego_rmse_y,ego_rmse_theta,static_rmse_x,static_rmse_y,"
	      "ate,ate_aligned,ms_per_step\n";
	os.precision(10);
	for (const auto& r : results)
	{
		const auto& m = r.metrics;
		os << r.level << "," << r.run << "," << r.seed << "," << r.steps << "," << m.ego.x << ","
		   << m.ego.y << "," << m.ego.theta << "," << m.static_map.x << "," << m.static_map.y << ","
		   << m.ate << "," << m.ate_aligned << "," << m.ms_per_step << "\n";
	}
}

void CMonteCarloApp::writeShard()
{
	makeOutputDir(outDir);
	eval::TRunRecordFile f;
	// Everything that must agree between the shards of one sweep (checked by --merge).
	f.sweep = {{"levels", joined(levels)},
	           {"runs", std::to_string(runs)},
	           {"seed", std::to_string(seed)},
	           {"backend", backend},
	           {"initial_covariance", sigma0FromLevel ? "sigma_w" : "ini"},
	           {"scenario", std::filesystem::path(scenarioFile).filename().string()},
	           {"shards", std::to_string(shardCount)},
	           {"shard", std::to_string(shardIndex)}};
	for (const auto& r : results)
		f.runs.push_back({r.level, r.run, r.seed, r.steps, r.metrics, r.consistency});
	const std::string name =
	    "shard_" + std::to_string(shardIndex) + "_of_" + std::to_string(shardCount) + ".runs";
	auto out = [&](const std::string& n, const std::function<void(std::ostream&)>& w)
	{
		const std::string p = joinPath(outDir, n);
		eval::writeFile(p, w);
		writtenFiles.push_back(p);
	};
	out(name, [&](std::ostream& os) { eval::writeRunRecords(os, f); });
	out("runs.csv", [&](std::ostream& os) { writeRunsCsv(os); });
	out("effective_config.ini",
	    [&](std::ostream& os)
	    {
		    os << "# dynslam-montecarlo shard " << shardIndex << "/" << shardCount
		       << "\n# config: " << iniFile << "\n# scenario: " << scenarioFile << "\n\n"
		       << params.getContent() << "\n";
	    });
	std::cout << "shard " << shardIndex << "/" << shardCount << ": " << results.size()
	          << " runs in " << wallSeconds << " s; wrote " << joinPath(outDir, name)
	          << " (merge the shards with dynslam-montecarlo --merge DIR... --out DIR)\n";
}

void CMonteCarloApp::runMerge()
{
	namespace fs = std::filesystem;
	mergedFiles.clear();
	for (const auto& d : mergeDirs)
	{
		std::error_code ec;
		if (!fs::is_directory(d, ec))
			throw std::runtime_error("--merge: '" + d + "' is not a folder");
		std::vector<std::string> here;
		for (const auto& e : fs::directory_iterator(d))
			if (e.is_regular_file() && e.path().extension() == ".runs")
				here.push_back(e.path().string());
		if (here.empty()) throw std::runtime_error("--merge: no *.runs file in '" + d + "'");
		std::sort(here.begin(), here.end());
		mergedFiles.insert(mergedFiles.end(), here.begin(), here.end());
	}
	std::map<std::string, std::string> sweep;
	std::map<std::pair<std::string, int>, TRunResult> byKey;
	for (const auto& path : mergedFiles)
	{
		std::ifstream is(path);
		if (!is) throw std::runtime_error("cannot read '" + path + "'");
		eval::TRunRecordFile f = eval::readRunRecords(is, path);
		auto common = f.sweep;
		common.erase("shard");
		if (sweep.empty())
			sweep = common;
		else if (common != sweep)
			throw std::runtime_error("--merge: '" + path +
			                         "' belongs to another sweep (levels, runs, seed, backend, "
			                         "scenario or number of shards differ from '" +
			                         mergedFiles.front() + "')");
		for (auto& r : f.runs)
		{
			TRunResult res;
			res.level = r.level;
			res.run = r.run;
			res.seed = r.seed;
			res.steps = r.steps;
			res.metrics = std::move(r.metrics);
			res.consistency = std::move(r.consistency);
			if (!byKey.emplace(std::make_pair(res.level, res.run), std::move(res)).second)
				throw std::runtime_error("--merge: run " + r.level + "/" + std::to_string(r.run) +
				                         " appears twice (in '" + path + "')");
		}
	}
	levels = splitList(sweep["levels"]);
	runs = std::stoi(sweep["runs"]);
	seed = std::stoull(sweep["seed"]);
	backend = sweep["backend"];
	results.clear();
	for (const auto& l : levels)
		for (int r = 0; r < runs; ++r)
		{
			const auto it = byKey.find({l, r});
			if (it == byKey.end())
				throw std::runtime_error(
				    "--merge: run " + std::to_string(r) + " of level " + l + " is in none of the " +
				    std::to_string(mergedFiles.size()) + " record files (a shard missing?)");
			results.push_back(it->second);
		}
	if (byKey.size() != results.size())
		throw std::runtime_error("--merge: the records hold runs outside the sweep's grid");
	meanMsPerStep = 0;
	for (const auto& r : results) meanMsPerStep += r.metrics.ms_per_step / double(results.size());
	aggregate();
	printTables();
	std::cout << "\nmerged " << results.size() << " runs (" << levels.size() << " levels x " << runs
	          << ") from " << mergedFiles.size() << " record file(s); filter " << meanMsPerStep
	          << " ms/step\n";
	if (!outDir.empty()) writeOutputs();
}
}  // namespace dynslam::apps
