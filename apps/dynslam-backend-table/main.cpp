/** dynslam-backend-table: every back-end on the highway Monte Carlo (doc/backends.md). */
#include <dynslam/apps/app_main.h>
#include <dynslam/apps/backend_table.h>
#include <dynslam/apps/run_outputs.h>
#include <dynslam/common/app_support.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace
{
int run(int argc, const char** argv)
{
	const std::string app = "dynslam-backend-table";
	TCLAP::CmdLine cmd(app + ": every back-end on the same Monte Carlo", ' ', "0.1");
	// The flags of the other apps (doc/apps.md, "Command-line flags"); -s/--scenario and an
	// -o FILE.md are the old spellings, still accepted.
	TCLAP::ValueArg<std::string> ini("c", "config", "scenario INI (e.g. config/highway.ini)", false,
	                                 "", "file.ini", cmd);
	TCLAP::ValueArg<std::string> iniOld("s", "scenario", "deprecated spelling of -c/--config",
	                                    false, "", "file.ini", cmd);
	TCLAP::ValueArg<int> runs("n", "runs", "Monte Carlo runs", false, 3, "N", cmd);
	TCLAP::ValueArg<int> steps("k", "steps", "steps (-1: the scenario's)", false, -1, "K", cmd);
	TCLAP::ValueArg<std::string> noise("l", "noise", "noise level w1v1..w3v3", false, "w2v2", "L",
	                                   cmd);
	TCLAP::ValueArg<int> window("w", "window", "window size W", false, 10, "W", cmd);
	TCLAP::ValueArg<double> sxi("x", "sigma-xi", "Sigma_xi = value * I", false, 0.1, "s", cmd);
	TCLAP::ValueArg<std::string> out(
	    "o", "out", "also write the table as DIR/backend_table.md (created if missing)", false, "",
	    "DIR", cmd);
	TCLAP::SwitchArg quiet("q", "quiet", "no table on stdout (only with -o)", cmd);
	if (!dynslam::parseCommandLine(cmd, argc, argv, app)) return 0;  // --help, --version
	if (ini.isSet() == iniOld.isSet())
		throw std::invalid_argument(
		    "bad command line: give the scenario INI with -c/--config (see " + app + " --help)");
	// -o FILE.md: the old meaning (a file), kept.
	const std::string o = out.getValue();
	const bool oldFile = std::filesystem::path(o).extension() == ".md";
	const std::string mdFile = o.empty() ? "" : oldFile ? o : o + "/backend_table.md";
	if (!o.empty()) dynslam::apps::checkOutputFile(mdFile, "-o/--out");
	dynslam::apps::TBackendTableOptions opts;
	opts.scenario_ini = ini.isSet() ? ini.getValue() : iniOld.getValue();
	opts.runs = runs.getValue();
	opts.steps = steps.getValue();
	opts.noise_level = noise.getValue();
	opts.window_size = window.getValue();
	opts.sigma_xi = sxi.getValue();
	const auto rows = dynslam::apps::runBackendTable(opts);
	if (!quiet.getValue()) dynslam::apps::writeBackendTableMarkdown(std::cout, rows);
	if (!mdFile.empty())
	{
		if (!oldFile) dynslam::apps::makeOutputDir(o);
		std::ofstream f(mdFile);
		dynslam::apps::writeBackendTableMarkdown(f, rows);
		if (!f) throw std::runtime_error("cannot write '" + mdFile + "'");
	}
	return 0;
}
}  // namespace

int main(int argc, const char** argv)
{
	return dynslam::apps::runMain("dynslam-backend-table", [&] { return run(argc, argv); });
}
