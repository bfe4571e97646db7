/** dynslam-backend-table: every back-end on the highway Monte Carlo (doc/backends.md). */
#include <dynslam/apps/backend_table.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <fstream>
#include <iostream>

int main(int argc, char** argv)
{
	try
	{
		TCLAP::CmdLine cmd("dynslam-backend-table: every back-end on the same Monte Carlo", ' ');
		TCLAP::ValueArg<std::string> ini("s", "scenario", "scenario INI", true, "", "file", cmd);
		TCLAP::ValueArg<int> runs("n", "runs", "Monte Carlo runs", false, 3, "N", cmd);
		TCLAP::ValueArg<int> steps("k", "steps", "steps (-1: the scenario's)", false, -1, "K", cmd);
		TCLAP::ValueArg<std::string> noise("l", "noise", "noise level w1v1..w3v3", false, "w2v2",
		                                   "L", cmd);
		TCLAP::ValueArg<int> window("w", "window", "window size W", false, 10, "W", cmd);
		TCLAP::ValueArg<double> sxi("x", "sigma-xi", "Sigma_xi = value * I", false, 0.1, "s", cmd);
		TCLAP::ValueArg<std::string> out("o", "out", "also write the Markdown table here", false,
		                                 "", "file", cmd);
		// MRPT's TCLAP returns false both for --help/--version (exit 0) and for errors
		// (after printing them; exit 1).
		if (!cmd.parse(argc, argv))
		{
			for (int i = 1; i < argc; ++i)
			{
				const std::string a = argv[i];
				if (a == "-h" || a == "--help" || a == "--version") return 0;
			}
			return 1;
		}
		dynslam::apps::TBackendTableOptions o;
		o.scenario_ini = ini.getValue();
		o.runs = runs.getValue();
		o.steps = steps.getValue();
		o.noise_level = noise.getValue();
		o.window_size = window.getValue();
		o.sigma_xi = sxi.getValue();
		const auto rows = dynslam::apps::runBackendTable(o);
		dynslam::apps::writeBackendTableMarkdown(std::cout, rows);
		if (!out.getValue().empty())
		{
			std::ofstream f(out.getValue());
			dynslam::apps::writeBackendTableMarkdown(f, rows);
		}
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-backend-table: error: " << e.what() << "\n";
		return 1;
	}
}
