#include <dynslam/common/app_support.h>
#include <dynslam/mrclam/CMrclamApp.h>
#include <dynslam/mrclam/anonymous.h>
#include <dynslam/mrclam/rawlog_writer.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace dynslam::mrclam
{
CMrclamApp::CMrclamApp() : mrpt::system::COutputLogger("dynslam-mrclam") {}

bool CMrclamApp::initialize(int argc, const char** argv)
{
	TCLAP::CmdLine cmd(
	    "dynslam-mrclam: converts one robot of a UTIAS MRCLAM dataset folder into an MRPT "
	    "rawlog (landmarks as static IDs, the other robots as one-feature moving objects) plus "
	    "ground truth, or estimates the noise parameters from the ground truth.",
	    ' ', "0.1");
	TCLAP::ValueArg<std::string> argDataset(
	    "", "dataset", "MRCLAM dataset folder (Barcodes.dat, RobotN_*.dat, ...)", true, "", "DIR",
	    cmd);
	TCLAP::ValueArg<int> argRobot("", "robot", "ego robot, 1..5", false, 0, "N", cmd);
	TCLAP::ValueArg<std::string> argOut("o", "out", "output folder (required for an import)", false,
	                                    "", "DIR", cmd);
	TCLAP::ValueArg<std::string> argConfig(
	    "c", "config", "INI with a [MRCLAM_Import] section (e.g. config/mrclam.ini)", false, "",
	    "INI", cmd);
	TCLAP::ValueArg<double> argDuration(
	    "", "duration", "only the first S seconds of measurements (overrides the INI)", false, 0,
	    "S", cmd);
	TCLAP::ValueArg<std::string> argBase(
	    "", "base", "base name of the output files (default robotN)", false, "", "B", cmd);
	TCLAP::SwitchArg argAnon("", "anonymous",
	                         "anonymous IDs: robots and landmarks permuted into one range 0..19 "
	                         "(issue 12, doc/results/real-data.md section 6)",
	                         cmd);
	TCLAP::ValueArg<unsigned> argSeed("", "seed", "with --anonymous: the permutation's seed", false,
	                                  1, "S", cmd);
	TCLAP::SwitchArg argNoise("", "estimate-noise",
	                          "estimate measurement and odometry noise from the ground truth", cmd);
	TCLAP::SwitchArg argAll("", "all-robots", "with --estimate-noise: robots 1..5", cmd);
	TCLAP::ValueArg<int> argLeaveOut("", "leave-out",
	                                 "with --all-robots: estimate on the other four robots (1..5)",
	                                 false, 0, "N", cmd);

	TCLAP::SwitchArg argQuiet("q", "quiet", "Only warnings and errors (no import summary)", cmd);
	if (!parseCommandLine(cmd, argc, argv, "dynslam-mrclam")) return false;  // --help
	quiet = argQuiet.getValue();
	if (quiet) setMinLoggingLevel(mrpt::system::LVL_WARN);
	dataset_dir = argDataset.getValue();
	robot = argRobot.getValue();
	out_dir = argOut.getValue();
	config_file = argConfig.getValue();
	base = argBase.getValue();
	estimate_noise = argNoise.getValue();
	all_robots = argAll.getValue();
	leave_out = argLeaveOut.getValue();
	anonymous = argAnon.getValue();
	anonymous_seed = argSeed.getValue();
	if (argSeed.isSet() && !anonymous) throw std::invalid_argument("--seed needs --anonymous");
	if (anonymous && estimate_noise)
		throw std::invalid_argument("--anonymous is an import option, not for --estimate-noise");
	if (argLeaveOut.isSet() && (!all_robots || !isRobotSubject(leave_out)))
		throw std::invalid_argument("--leave-out needs --all-robots and a robot 1..5");
	if (!config_file.empty()) loadSectionOfFile(config_file, "MRCLAM_Import", options);
	if (argDuration.isSet())
	{
		if (!(argDuration.getValue() > 0)) throw std::invalid_argument("--duration must be > 0");
		options.import.duration = argDuration.getValue();
	}
	return true;
}

void CMrclamApp::run()
{
	if (dataset_dir.empty()) throw std::invalid_argument("--dataset is required");
	if (!std::filesystem::is_directory(dataset_dir))
		throw std::runtime_error(dataset_dir + ": dataset folder not found");
	if (estimate_noise)
		runNoiseEstimation();
	else
		runImport();
}

void CMrclamApp::runImport()
{
	if (!isRobotSubject(robot)) throw std::invalid_argument("--robot must be 1..5");
	if (out_dir.empty()) throw std::invalid_argument("--out is required for an import");
	const std::string b = base.empty() ? "robot" + std::to_string(robot) : base;
	const TDataset data = loadDataset(dataset_dir, robot);
	TImportResult res = importRobot(data, options.import);
	if (anonymous) makeAnonymous(res, anonymous_seed);
	summary = res.summary;
	writeImport(res, options, out_dir, b);
	const std::string text = summary.toText();
	if (!quiet) std::cout << text;
	logFmt(mrpt::system::LVL_INFO, "wrote %s/%s.rawlog (%zu steps) and ground truth",
	       out_dir.c_str(), b.c_str(), summary.steps);
}

void CMrclamApp::runNoiseEstimation()
{
	std::vector<int> robots;
	if (all_robots)
		for (int r = kFirstRobot; r <= kLastRobot; r++)
		{
			if (r != leave_out) robots.push_back(r);
		}
	else if (isRobotSubject(robot))
		robots.push_back(robot);
	else
		throw std::invalid_argument("--estimate-noise needs --robot 1..5 or --all-robots");
	std::ostringstream report;
	TNoiseSamples pooled;
	std::vector<double> delays;
	for (int i = 0; i <= 10; i++) delays.push_back(0.05 * i);
	std::vector<TDelayScore> pooledDelays;
	const double f = options.noise_outlier_factor, chi2 = options.noise_trim_chi2;
	for (int r : robots)
	{
		const TDataset data = loadDataset(dataset_dir, r);
		const TImportResult res = importRobot(data, options.import);
		summary = res.summary;
		const TNoiseSamples s = collectNoiseSamples(data, res);
		pooled.append(s);
		noise_per_robot[r] = estimateNoise(s, f, chi2);
		const auto scores = scoreOdometryDelays(data, res, delays, options.import.odometry_scale_v,
		                                        options.import.odometry_scale_w);
		poolDelayScores(pooledDelays, scores);
		delay_per_robot[r] = bestDelay(scores).delay;
		report << "=== robot " << r << " (" << res.summary.steps << " steps, "
		       << res.summary.duration() << " s; odometry integrated with delay "
		       << options.import.odometry_delay << " s, gains v " << options.import.odometry_scale_v
		       << ", w " << options.import.odometry_scale_w << ")\n"
		       << noise_per_robot[r].toText() << delayScoresText(scores)
		       << deadReckoningText(deadReckoning(res, {10, 30, 60, 120, 300})) << "\n";
	}
	noise_pooled = estimateNoise(pooled, f, chi2);
	if (robots.size() > 1) report << "=== pooled, robots";
	if (robots.size() > 1)
		for (int r : robots) report << " " << r;
	if (robots.size() > 1)
		report << "\n" << noise_pooled.toText() << delayScoresText(pooledDelays) << "\n";
	delay_pooled = bestDelay(pooledDelays).delay;
	noise_pooled.delay_estimate = delay_pooled;
	noise_pooled.scale_v_estimate =
	    options.import.odometry_scale_v * noise_pooled.odo_translation_gain;
	report << "Suggested INI values (inlier std; fitted odometry model):\n" << noise_pooled.toIni();
	std::cout << report.str();
	if (!out_dir.empty())
	{
		std::filesystem::create_directories(out_dir);
		const std::string p = out_dir + "/noise_estimate.txt";
		std::ofstream o(p);
		o << report.str();
		if (!o) throw std::runtime_error(p + ": write error");
		const std::string pi = out_dir + "/noise_estimate.ini";
		std::ofstream oi(pi);
		oi << noise_pooled.toIni();
		if (!oi) throw std::runtime_error(pi + ": write error");
	}
}
}  // namespace dynslam::mrclam
