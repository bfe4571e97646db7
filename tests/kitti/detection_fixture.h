#pragma once
/** Hand-written detection and calibration files in the PointRCNN/AB3DMOT and KITTI formats
 * (numbers made up here; nothing of a real detection file) for the importer's tests. */
#include <dynslam/kitti/CKittiApp.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mini_sequence.h"

namespace kitti_test
{
namespace fs = std::filesystem;
/** frame, class, x1, y1, x2, y2, score, h, w, l, x, y, z, rot_y, alpha */
inline std::string det(int frame, int cls, double score, double x, double z, double ry = -1.5)
{
	return std::to_string(frame) + "," + std::to_string(cls) + ",100.5,150.25,300,250.75," +
	       std::to_string(score) + ",1.5,1.7,4.1," + std::to_string(x) + ",1.6," +
	       std::to_string(z) + "," + std::to_string(ry) + ",-1.2";
}

inline std::vector<std::string> calibLines()
{
	return {"P0: 700 0 600 0 0 700 180 0 0 0 1 0",
	        "P1: 700 0 600 -380 0 700 180 0 0 0 1 0",
	        "P2: 700 0 600 45 0 700 180 0.2 0 0 1 0.003",
	        "P3: 700 0 600 -330 0 700 180 1.5 0 0 1 0.004",
	        "R0_rect: 1 0 0 0 1 0 0 0 1",
	        "Tr_velo_to_cam: 0 -1 0 0.1 0 0 -1 -0.07 1 0 0 -0.3",
	        "Tr_imu_to_velo: 1 0 0 -0.8 0 1 0 0.3 0 0 1 -0.9"};
}

/** A mini sequence (12 frames) with detections DIR/det/{Car,Cyclist}/0007.txt and the
 * calibration DIR/calib/0007.txt; returns DIR. */
inline std::string writeSet(const std::string& name, const std::vector<std::string>& cars,
                            const std::vector<std::string>& cyclists = {},
                            const std::vector<std::string>& calib = calibLines())
{
	const std::string d = writeMiniSequence(name, 12);
	fs::create_directories(d + "/det/Car");
	fs::create_directories(d + "/det/Cyclist");
	fs::create_directories(d + "/calib");
	writeLines(d + "/det/Car/0007.txt", cars);
	writeLines(d + "/det/Cyclist/0007.txt", cyclists);
	writeLines(d + "/calib/0007.txt", calib);
	return d;
}

/** Runs the app with detections; returns the error text ("" on success). */
inline std::string runApp(const std::string& d, dynslam::kitti::CKittiApp& app,
                          const std::string& extraIni = "")
{
	app.labels_dir = d + "/label_02";
	app.poses_dir = d + "/poses";
	app.sequence = "0007";
	app.out_dir = d + "/out";
	app.detections_dir = d + "/det";
	app.calib_dir = d + "/calib";
	if (!extraIni.empty())
	{
		mrpt::config::CConfigFileMemory ini("[KITTI_Import]\n" + extraIni + "\n");
		app.options.loadFromConfigFile(ini, "KITTI_Import");
	}
	try
	{
		app.run();
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}

/** dynslam-kitti --simulate-detections on sequence 0000 of labelsDir/posesDir: detection files
 * into d/det, the import into d/out; `import` is the [KITTI_Import] section's INI, `simulate`
 * the [KITTI_SimulateDetections] one. */
inline void simulateAndImport(dynslam::kitti::CKittiApp& app, const std::string& labelsDir,
                              const std::string& posesDir, const std::string& d,
                              const mrpt::config::CConfigFileBase& import,
                              const mrpt::config::CConfigFileBase& simulate)
{
	app.labels_dir = labelsDir;
	app.poses_dir = posesDir;
	app.sequence = "0000";
	app.out_dir = d + "/out";
	app.simulate_dir = d + "/det";
	app.quiet = true;
	app.options.loadFromConfigFile(import, "KITTI_Import");
	app.simulate_options.loadFromConfigFile(simulate, "KITTI_SimulateDetections");
	app.run();
}
}  // namespace kitti_test
