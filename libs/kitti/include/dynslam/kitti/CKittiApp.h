#pragma once
/** @file CKittiApp.h
 * The dynslam-kitti app (a thin main() around this class):
 *
 *   dynslam-kitti --labels DIR --poses DIR --sequence SSSS --out DIR [-c INI] [--anonymous]
 *                 [--base B] [--detections DIR --calib DIR | --simulate-detections DIR]
 *
 * Reads DIR/SSSS.txt of the labels (label_02) and of the poses, converts them (import.h) and
 * writes into --out `<B>.rawlog` and the ground truth (rawlog_writer.h); B defaults to
 * kitti_SSSS. Everything is read and checked before anything is written.
 * --detections DIR --calib DIR (both or neither): the detector's boxes DIR/CLASS/SSSS.txt for
 * the classes of detection_classes and the calibration DIR/SSSS.txt are read and checked
 * (detection_files.h), counted per class and frame in the summary, and written to the rawlog
 * as the steps' only readings (detection_import.h: DETECTION_BOXES,
 * dynslam/common/detection_boxes.h); the ground truth is still the labels'.
 * --simulate-detections DIR (instead of --detections and --calib): a synthetic detector
 * (detection_simulator.h, INI section [KITTI_SimulateDetections] of -c) makes detections from
 * the labels and writes them into DIR/CLASS/SSSS.txt with a nominal calibration
 * DIR/calib/SSSS.txt; the import then reads them as with --detections DIR --calib DIR/calib. */
#include <dynslam/kitti/CKittiOptions.h>
#include <dynslam/kitti/import.h>
#include <mrpt/system/COutputLogger.h>

#include <string>
#include <vector>

namespace dynslam::kitti
{
class CKittiApp : public mrpt::system::COutputLogger
{
public:
	CKittiApp();
	/** Parses the command line and loads the INI. Returns false when the program should stop
	 * (help or version shown: exit code 0). Throws std::invalid_argument on a bad command
	 * line, std::runtime_error / std::invalid_argument naming the file on a bad INI. */
	bool initialize(int argc, const char** argv);
	/** Reads, converts and writes. Throws std::runtime_error on bad input (nothing written). */
	void run();

	// --- settings (filled by initialize(), or set directly by tests) ---
	std::string labels_dir, poses_dir, sequence, out_dir, config_file, base;
	std::string detections_dir, calib_dir;  ///< both empty: no detections
	std::string simulate_dir;               ///< --simulate-detections (empty: none)
	TKittiOptions options;
	TKittiSimOptions simulate_options;  ///< [KITTI_SimulateDetections]
	bool quiet = false;                 ///< -q: no summary on stdout, only warnings and errors

	// --- results ---
	TImportSummary summary;
	TDetectionSummary detection_summary;  ///< with --detections
	std::vector<std::string> written;

private:
	/** --simulate-detections: labels -> detection files and calibration in simulate_dir. */
	void simulateDetectionFiles();
};

/** Reads and converts one sequence (no output): DIR/SSSS.txt of labels and poses. */
TImportResult importFromFiles(const std::string& labelsDir, const std::string& posesDir,
                              const std::string& sequence, const TImportOptions& opts);
}  // namespace dynslam::kitti
