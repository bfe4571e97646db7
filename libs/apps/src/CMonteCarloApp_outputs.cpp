// Output files of dynslam-montecarlo (CMonteCarloApp::writeOutputs) and the NEES Markdown table.
#include <dynslam/apps/CMonteCarloApp.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/writers.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace dynslam::apps
{
namespace
{
std::string num(double v, const char* fmt = "%.3f")
{
	if (!std::isfinite(v)) return "-";
	char b[48];
	std::snprintf(b, sizeof(b), fmt, v);
	return b;
}
std::string cell(const eval::TConsistencyStats& s)
{
	if (s.rows.empty()) return "-";
	return num(s.anees) + " [" + num(s.anees_lower) + ", " + num(s.anees_upper) + "], " +
	       num(100.0 * s.fraction_inside, "%.0f") + "%";
}
}  // namespace

void writeNeesMarkdown(std::ostream& os,
                       const std::vector<std::pair<std::string, eval::TConsistencySummary>>& nees)
{
	std::vector<int32_t> objects;
	for (const auto& [l, s] : nees)
		for (const auto& [o, st] : s.object_poses)
			if (std::find(objects.begin(), objects.end(), o) == objects.end()) objects.push_back(o);
	std::sort(objects.begin(), objects.end());
	os << "| level | runs | ego NEES | static map NEES | landmark NEES |";
	for (int32_t o : objects) os << " object " << o << " pose NEES |";
	os << " NIS |\n|---|---|---|---|---|";
	for (size_t i = 0; i < objects.size(); ++i) os << "---|";
	os << "---|\n";
	for (const auto& [l, s] : nees)
	{
		os << "| " << l << " | " << s.runs << " | " << cell(s.ego) << " | " << cell(s.map) << " | "
		   << cell(s.landmarks) << " |";
		for (int32_t o : objects)
		{
			const auto it = s.object_poses.find(o);
			os << " " << (it == s.object_poses.end() ? std::string("-") : cell(it->second)) << " |";
		}
		os << " " << cell(s.nis) << " |\n";
	}
	os << "\nEach cell: ANEES (sum of NEES / sum of dof; 1 if consistent) [two-sided 95% bounds of "
	      "the ANEES], share of keys (steps; landmarks; the one whole-map sample) whose average "
	      "over "
	      "the runs lies inside its own 95% bounds. Static map: all landmarks jointly"
	   << (nees.empty() || nees.front().second.map_joint_cov ? " (joint covariance)"
	                                                         : " (block-diagonal covariance)")
	   << ", one sample per run.\n";
}

void CMonteCarloApp::writeOutputs()
{
	std::filesystem::create_directories(outDir);
	auto out = [&](const std::string& name, const std::function<void(std::ostream&)>& w)
	{
		const std::string p = joinPath(outDir, name);
		eval::writeFile(p, w);
		writtenFiles.push_back(p);
	};
	out("table1.md",
	    [&](std::ostream& os)
	    {
		    os << "# Table I: RMSE averaged over " << runs
		       << " run(s) per noise level (ours / paper)\n\n";
		    eval::writeTable1Markdown(os, table);
	    });
	out("table1.csv", [&](std::ostream& os) { eval::writeTable1Csv(os, table); });
	out("nees_summary.csv", [&](std::ostream& os) { eval::writeConsistencySummaryCsv(os, nees); });
	out("nees_summary.md",
	    [&](std::ostream& os)
	    {
		    os << "# NEES / NIS per noise level (" << runs << " run(s) each)\n\n";
		    writeNeesMarkdown(os, nees);
	    });
	out("runs.csv",
	    [&](std::ostream& os)
	    {
		    os << "level,run,seed,steps,ego_rmse_x,ego_rmse_y,ego_rmse_theta,static_rmse_x,static_"
		          "rmse_y,"
		          "ate,ate_aligned,ms_per_step\n";
		    os.precision(10);
		    for (const auto& r : results)
		    {
			    const auto& m = r.metrics;
			    os << r.level << "," << r.run << "," << r.seed << "," << r.steps << "," << m.ego.x
			       << "," << m.ego.y << "," << m.ego.theta << "," << m.static_map.x << ","
			       << m.static_map.y << "," << m.ate << "," << m.ate_aligned << "," << m.ms_per_step
			       << "\n";
		    }
	    });
	for (const auto& [l, s] : nees)
		out("nees_ego_" + l + ".csv",
		    [&](std::ostream& os) { eval::writeConsistencyCsv(os, s.ego); });
	out("effective_config.ini",
	    [&](std::ostream& os)
	    {
		    os << "# Effective configuration of dynslam-montecarlo\n# config: " << iniFile
		       << "\n# scenario: " << scenarioFile << "\n# runs per level: " << runs
		       << ", threads: " << threadsUsed << ", base seed: " << seed
		       << "\n# per level, [DynamicKFSLAM] Sigma_v and Sigma_0 are set from the level "
		          "(Sigma_0 = "
		          "Sigma_w)\n\n"
		       << params.getContent() << "\n\n# ---- scenario (effective) ----\n";
		    scenario.dumpToTextStream(os);
	    });
	if (figures)
		for (const auto& [l, s] : nees)
		{
			if (s.ego.rows.empty()) continue;
			eval::TConsistencyFigureOptions fo;
			fo.title = "Ego NEES " + l + " (" + std::to_string(s.runs) + " runs)";
			const std::string p = joinPath(outDir, "nees_ego_" + l + ".png");
			eval::savePng(eval::drawConsistencyFigure(s.ego, fo), p);
			writtenFiles.push_back(p);
		}
	std::cout << "wrote " << writtenFiles.size() << " files into " << outDir << "\n";
}
}  // namespace dynslam::apps
