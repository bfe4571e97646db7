#pragma once
/** @file CKittiOptions.h
 * INI options of the KITTI importer, section [KITTI_Import] (config/kitti.ini). Every key is
 * optional (defaults: the values of config/kitti.ini); unknown keys and invalid values are
 * rejected with "[KITTI_Import] key = 'value': reason". The anonymous mode is a command-line
 * switch (--anonymous), not a key. The detection reader's keys (used with --detections):
 * detection_classes (a list of Car, Pedestrian, Cyclist) and detection_min_score (a number, or
 * none: every detection kept). */
#include <dynslam/kitti/detection_files.h>
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
}  // namespace dynslam::kitti
