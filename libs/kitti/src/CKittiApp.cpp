#include <dynslam/common/app_support.h>
#include <dynslam/kitti/CKittiApp.h>
#include <dynslam/kitti/detection_import.h>
#include <dynslam/kitti/kitti_files.h>
#include <dynslam/kitti/rawlog_writer.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace dynslam::kitti
{
TImportResult importFromFiles(const std::string& labelsDir, const std::string& posesDir,
                              const std::string& sequence, const TImportOptions& opts)
{
	checkSequenceName(sequence);
	for (const auto& d : {labelsDir, posesDir})
		if (!std::filesystem::is_directory(d)) throw std::runtime_error(d + ": folder not found");
	const std::string lp = sequenceFile(labelsDir, sequence), pp = sequenceFile(posesDir, sequence);
	if (!std::filesystem::exists(lp))
		throw std::runtime_error(lp + ": file not found (no sequence " + sequence + " in " +
		                         labelsDir + ")");
	if (!std::filesystem::exists(pp))
		throw std::runtime_error(pp + ": file not found (no sequence " + sequence + " in " +
		                         posesDir + ")");
	const auto poses = readPoses(pp);
	const auto labels = readLabels(lp);
	checkLabelsAgainstPoses(labels, poses.size(), pp);
	return importSequence(poses, labels, opts, sequence);
}

CKittiApp::CKittiApp() : mrpt::system::COutputLogger("dynslam-kitti") {}

void CKittiApp::simulateDetectionFiles()
{
	checkSequenceName(sequence);
	const std::string pp = sequenceFile(poses_dir, sequence),
	                  lp = sequenceFile(labels_dir, sequence);
	for (const auto& f : {pp, lp})
		if (!std::filesystem::is_regular_file(f)) throw std::runtime_error(f + ": file not found");
	const auto poses = readPoses(pp);
	const auto labels = readLabels(lp);
	checkLabelsAgainstPoses(labels, poses.size(), pp);
	const auto dets = simulateDetections(labels, poses.size(), simulate_options.sim);
	writeDetectionFiles(dets, simulate_dir, sequence);
	writeNominalCalib((std::filesystem::path(simulate_dir) / "calib").string(), sequence);
	logFmt(mrpt::system::LVL_INFO, "simulated %zu detections into %s", dets.size(),
	       simulate_dir.c_str());
}

bool CKittiApp::initialize(int argc, const char** argv)
{
	TCLAP::CmdLine cmd(
	    "dynslam-kitti: converts one KITTI tracking sequence (3-D box labels with track IDs and a "
	    "camera trajectory) into a bird's-eye MRPT rawlog (box footprint corners as range-bearing "
	    "readings; static tracks as landmarks, moving ones as objects, or all anonymous) plus "
	    "ground truth. See doc/kitti.md.",
	    ' ', "0.1");
	TCLAP::ValueArg<std::string> aLabels(
	    "", "labels", "folder of the label files (label_02/SSSS.txt)", true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> aPoses("", "poses", "folder of the pose files (poses/SSSS.txt)",
	                                    true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> aSeq("", "sequence", "sequence, four digits (e.g. 0000)", true, "",
	                                  "SSSS", cmd);
	TCLAP::ValueArg<std::string> aOut("o", "out", "output folder", true, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> aCfg("c", "config",
	                                  "INI with a [KITTI_Import] section (config/kitti.ini)", false,
	                                  "", "INI", cmd);
	TCLAP::ValueArg<std::string> aBase(
	    "", "base", "base name of the output files (default kitti_SSSS)", false, "", "B", cmd);
	TCLAP::ValueArg<std::string> aDet(
	    "", "detections",
	    "folder of 3-D detections DIR/CLASS/SSSS.txt: the rawlog's readings are then the "
	    "detector's boxes (needs --calib)",
	    false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> aCalib("", "calib", "folder of calibration files DIR/SSSS.txt",
	                                    false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> aSim(
	    "", "simulate-detections",
	    "write synthetic detections made from the labels (INI section [KITTI_SimulateDetections]) "
	    "into DIR, then import them as with --detections DIR --calib DIR/calib",
	    false, "", "DIR", cmd);
	TCLAP::SwitchArg aAnon("", "anonymous",
	                       "every track anonymous: IDs that say nothing about track or class", cmd);
	TCLAP::SwitchArg aQuiet("q", "quiet", "Only warnings and errors (no summary)", cmd);
	if (!parseCommandLine(cmd, argc, argv, "dynslam-kitti")) return false;  // --help
	quiet = aQuiet.getValue();
	if (quiet) setMinLoggingLevel(mrpt::system::LVL_WARN);
	labels_dir = aLabels.getValue();
	poses_dir = aPoses.getValue();
	sequence = aSeq.getValue();
	out_dir = aOut.getValue();
	config_file = aCfg.getValue();
	base = aBase.getValue();
	detections_dir = aDet.getValue();
	calib_dir = aCalib.getValue();
	simulate_dir = aSim.getValue();
	if (!config_file.empty())
	{
		loadSectionOfFile(config_file, "KITTI_Import", options);
		loadSectionOfFile(config_file, "KITTI_SimulateDetections", simulate_options);
	}
	options.import.anonymous = aAnon.getValue();
	return true;
}

void CKittiApp::run()
{
	if (out_dir.empty()) throw std::invalid_argument("--out is required");
	if (detections_dir.empty() != calib_dir.empty())
		throw std::invalid_argument("--detections and --calib go together");
	std::string detDir = detections_dir, calDir = calib_dir;
	if (!simulate_dir.empty())
	{
		if (!detDir.empty())
			throw std::invalid_argument("--simulate-detections replaces --detections and --calib");
		simulateDetectionFiles();
		detDir = simulate_dir;
		calDir = (std::filesystem::path(simulate_dir) / "calib").string();
	}
	TImportResult res = importFromFiles(labels_dir, poses_dir, sequence, options.import);
	if (!detDir.empty())
	{
		std::vector<std::vector<TKittiDetection>> kept;
		detection_summary =
		    readDetectionSet(detDir, calDir, sequence, options.detections, res.steps.size(),
		                     sequenceFile(poses_dir, sequence), &kept);
		applyDetections(kept, options.import.max_range, res, detection_summary);
		res.summary.detections_text = detection_summary.toText();
	}
	summary = res.summary;
	const std::string b = base.empty() ? "kitti_" + sequence : base;
	written = writeImport(res, options, out_dir, b);
	if (!quiet) std::cout << summary.toText();
	logFmt(mrpt::system::LVL_INFO, "wrote %s/%s.rawlog (%zu steps, %s) and ground truth",
	       out_dir.c_str(), b.c_str(), summary.steps,
	       res.detections             ? "detections"
	       : options.import.anonymous ? "anonymous"
	                                  : "labelled");
}
}  // namespace dynslam::kitti
