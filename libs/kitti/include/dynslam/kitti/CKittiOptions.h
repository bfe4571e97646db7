#pragma once
/** @file CKittiOptions.h
 * INI options of the KITTI importer, section [KITTI_Import] (config/kitti.ini). Every key is
 * optional (defaults: the values of config/kitti.ini); unknown keys and invalid values are
 * rejected with "[KITTI_Import] key = 'value': reason". The anonymous mode is a command-line
 * switch (--anonymous), not a key. The detection reader's keys (used with --detections):
 * detection_classes (a list of Car, Pedestrian, Cyclist) and detection_min_score (a number, or
 * none: every detection kept). */
#include <dynslam/kitti/detection_files.h>
#include <dynslam/kitti/detection_simulator.h>
#include <dynslam/kitti/import.h>
#include <mrpt/config/CLoadableOptions.h>

namespace dynslam::kitti
{
struct TKittiOptions : public mrpt::config::CLoadableOptions
{
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
	                        const std::string& section) override;
	void dumpToTextStream(std::ostream& out) const override;

	TImportOptions import;
	TDetectionOptions detections;
};

/** Section [KITTI_SimulateDetections] (dynslam-kitti --simulate-detections; every key optional,
 * defaults of TDetectionSimOptions; unknown keys and invalid values rejected): seed,
 * miss_probability, false_positives_per_frame, fp_min_range, fp_max_range, fp_fov_deg,
 * fp_score_min, fp_score_max, score_min, score_max, std_xy, std_yaw, std_size,
 * flip_probability (detection_simulator.h). */
struct TKittiSimOptions : public mrpt::config::CLoadableOptions
{
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
	                        const std::string& section) override;
	void dumpToTextStream(std::ostream& out) const override;

	TDetectionSimOptions sim;
};
}  // namespace dynslam::kitti
