#include <dynslam/common/app_support.h>
#include <dynslam/sim/CSimulateApp.h>
#include <dynslam/sim/figure.h>
#include <dynslam/sim/scenario.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::sim
{
CSimulateApp::CSimulateApp() : mrpt::system::COutputLogger("dynslam-simulate") {}

bool CSimulateApp::initialize(int argc, const char** argv)
{
	TCLAP::CmdLine cmd(
	    "dynslam-simulate: writes a scenario (the highway of the paper or a generated one) as an "
	    "MRPT rawlog with ground truth. See doc/simulator.md.",
	    ' ', "0.1");
	TCLAP::ValueArg<std::string> argConfig(
	    "c", "config", "Scenario INI file (e.g. config/highway.ini)", true, "", "file.ini", cmd);
	TCLAP::ValueArg<std::string> argOut("o", "out", "Output directory (created if missing)", false,
	                                    ".", "dir", cmd);
	TCLAP::ValueArg<std::string> argName(
	    "", "name", "Base name of the output files ([Scenario] name)", false, "", "base", cmd);
	TCLAP::ValueArg<std::string> argNoise(
	    "", "noise", "Noise level of eq. (5)-(7): w1v1..w3v3, or none ([Noise] level)", false, "",
	    "level", cmd);
	TCLAP::ValueArg<long> argWorldSeed("", "world-seed", "World seed ([Scenario] world_seed)",
	                                   false, -1, "n", cmd);
	TCLAP::ValueArg<long> argNoiseSeed("", "noise-seed", "Noise seed ([Scenario] noise_seed)",
	                                   false, -1, "n", cmd);
	TCLAP::ValueArg<long> argSteps("", "steps", "Number of steps ([Scenario] steps)", false, -1,
	                               "n", cmd);
	TCLAP::ValueArg<std::string> argFigure("", "figure", "Also draw the scenario into this PNG",
	                                       false, "", "file.png", cmd);
	TCLAP::SwitchArg argFigureOnly("", "figure-only", "Only draw the figure (needs --figure)", cmd);
	TCLAP::SwitchArg argStream(
	    "", "stream",
	    "Stream the simulation into the rawlog (long scenarios; no DA ground-truth file)", cmd);
	TCLAP::SwitchArg argQuiet("q", "quiet", "Only warnings and errors on the console", cmd);
	if (!parseCommandLine(cmd, argc, argv, "dynslam-simulate")) return false;  // --help
	if (argQuiet.getValue()) setMinLoggingLevel(mrpt::system::LVL_WARN);

	iniFile = argConfig.getValue();
	options = loadScenario(iniFile);
	outDir = argOut.getValue();
	if (!argName.getValue().empty()) options.name = argName.getValue();
	if (!argNoise.getValue().empty()) options.setNoiseLevel(argNoise.getValue());
	auto seed = [](long v, const char* flag)
	{
		if (v < 0 || v > long(UINT32_MAX))
			throw std::invalid_argument(std::string("--") + flag + " must be in [0, 4294967295]");
		return uint32_t(v);
	};
	if (argWorldSeed.isSet()) options.world_seed = seed(argWorldSeed.getValue(), "world-seed");
	if (argNoiseSeed.isSet()) options.noise_seed = seed(argNoiseSeed.getValue(), "noise-seed");
	if (argSteps.isSet())
	{
		if (argSteps.getValue() < 1) throw std::invalid_argument("--steps must be >= 1");
		options.steps = int(argSteps.getValue());
	}
	figureFile = argFigure.getValue();
	figureOnly = argFigureOnly.getValue();
	if (figureOnly && figureFile.empty())
		throw std::invalid_argument("--figure-only needs --figure");
	stream = argStream.getValue();
	options.validate();
	return true;
}

void CSimulateApp::run()
{
	options.validate();
	writtenFiles.clear();
	numRawlogEntries = numMeasurements = 0;
	groundTruth = buildGroundTruth(options);
	if (!figureFile.empty())
	{
		const auto parent = std::filesystem::path(figureFile).parent_path();
		if (!parent.empty()) std::filesystem::create_directories(parent);
		drawScenarioFigure(groundTruth, options, figureFile);
		writtenFiles.push_back(figureFile);
		MRPT_LOG_INFO_STREAM("Figure: " << figureFile);
	}
	if (figureOnly) return;

	{
		std::error_code ec;
		std::filesystem::create_directories(outDir, ec);
		if (ec || !std::filesystem::is_directory(outDir))
			throw std::runtime_error("cannot create the output folder '" + outDir +
			                         "': " + (ec ? ec.message() : "a file is in the way") +
			                         " (give another folder with -o)");
	}
	const std::string base = options.name;
	auto path = [&](const std::string& suffix)
	{ return (std::filesystem::path(outDir) / (base + suffix)).string(); };
	std::ostringstream ini;
	options.dumpToTextStream(ini);

	const std::string rawlog = path(".rawlog");
	if (stream)
		simulateToRawlog(groundTruth, options, options.noise_seed, rawlog, ini.str());
	else
	{
		const TSimulatedRun run = simulateMeasurements(groundTruth, options, options.noise_seed);
		writeRawlog(run, rawlog, ini.str());
		for (const auto& sf : run.frames)
			if (auto o = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>())
				numMeasurements += o->sensedData.size();
		writeKfSlamGroundTruth(groundTruth, run, outDir, base);
		io::writeClassGroundTruth(run.classes, path("_gt_classes.csv"));
		for (const char* s : {"_gt_landmarks.txt", "_gt_robot_path.txt", "_gt_data_association.txt",
		                      "_gt_classes.csv"})
			writtenFiles.push_back(path(s));
	}
	numRawlogEntries = 2 * groundTruth.numSteps();
	writtenFiles.push_back(rawlog);
	io::writeGroundTruth(groundTruth, outDir, base);
	for (const char* s : {"_gt_ego.csv", "_gt_ego.tum", "_gt_landmarks.csv", "_gt_objects.csv",
	                      "_gt_object_features.csv"})
		writtenFiles.push_back(path(s));
	{
		const std::string p = path("_scenario.ini");
		std::ofstream f(p, std::ios::binary);
		f << ini.str();
		if (!f) throw std::runtime_error("cannot write " + p);
		writtenFiles.push_back(p);
	}
	MRPT_LOG_INFO_STREAM("Scenario '" << options.name << "': " << groundTruth.numSteps()
	                                  << " poses, " << groundTruth.landmarks.size()
	                                  << " static landmarks, " << groundTruth.objects.size()
	                                  << " moving objects, noise " << options.noise_level
	                                  << ", seeds world " << options.world_seed << " noise "
	                                  << options.noise_seed);
	MRPT_LOG_INFO_STREAM("Rawlog: " << rawlog << " (" << numRawlogEntries << " entries, "
	                                << numMeasurements << " range-bearing readings)");
	for (const auto& f : writtenFiles) MRPT_LOG_INFO_STREAM("Wrote " << f);
}
}  // namespace dynslam::sim
