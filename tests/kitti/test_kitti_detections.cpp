/** The detection and calibration readers (detection_files.h) and `dynslam-kitti --detections
 * --calib` on hand-written lines in the PointRCNN/AB3DMOT format (numbers made up here; nothing
 * of a real detection file): good input is read and counted per class and frame; every bad
 * input is a std::runtime_error naming the file and line, and nothing is written. */
#include <dynslam/kitti/CKittiApp.h>
#include <dynslam/kitti/detection_files.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <filesystem>

#include "detection_fixture.h"

using namespace dynslam::kitti;
namespace fs = std::filesystem;
using namespace kitti_test;

namespace
{
std::string appError(const std::vector<std::string>& cars,
                     const std::vector<std::string>& calib = calibLines(), bool* wrote = nullptr)
{
	const std::string d = writeSet("bad_det", cars, {}, calib);
	CKittiApp app;
	const std::string e = runApp(d, app);
	if (wrote) *wrote = fs::exists(d + "/out");
	return e;
}

void expectContains(const std::string& s, const std::string& part)
{
	EXPECT_NE(s.find(part), std::string::npos) << "message: '" << s << "' lacks '" << part << "'";
}
}  // namespace

TEST(KittiDetections, ReadsTheFormat)
{
	const std::string d = writeSet("det_read", {det(0, 2, 7.25, -3, 10),
	                                            " 3 , 2 ,1,2,3,4, -0.5 "
	                                            ",1.4,1.6,3.9,4,1.7,8,0.3,0.1"});
	const TKittiDetectionFile f = readDetections(d + "/det/Car/0007.txt", "Car");
	ASSERT_EQ(f.detections.size(), 2u);
	const TKittiDetection& a = f.detections[0];
	EXPECT_EQ(a.frame, 0);
	EXPECT_EQ(a.type, "Car");
	EXPECT_EQ(a.x1, 100.5);
	EXPECT_EQ(a.y2, 250.75);
	EXPECT_EQ(a.score, 7.25);
	EXPECT_EQ(a.h, 1.5);
	EXPECT_EQ(a.w, 1.7);
	EXPECT_EQ(a.l, 4.1);
	EXPECT_EQ(a.x, -3);
	EXPECT_EQ(a.y, 1.6);
	EXPECT_EQ(a.z, 10);
	EXPECT_EQ(a.ry, -1.5);
	EXPECT_EQ(a.alpha, -1.2);
	EXPECT_EQ(f.detections[1].frame, 3);  // spaces around the commas are allowed
	EXPECT_EQ(f.detections[1].score, -0.5);
	EXPECT_EQ(f.detections[1].line, 2);
	EXPECT_EQ(f.max_frame, 3);
	EXPECT_EQ(detectionClassName(1), "Pedestrian");
	EXPECT_EQ(detectionClassName(3), "Cyclist");
	EXPECT_EQ(detectionClassName(4), "");
	const TKittiCalib c = readCalib(d + "/calib/0007.txt");
	EXPECT_EQ(c.P[2](0, 3), 45);
	EXPECT_EQ(c.P[3](2, 3), 0.004);
	EXPECT_EQ(c.Tr_velo_to_cam(1, 2), -1);
	EXPECT_EQ(c.Tr_imu_to_velo(2, 3), -0.9);
	EXPECT_TRUE(c.R0_rect.isIdentity());
	// the tracking benchmark's other spellings
	auto lines = calibLines();
	lines[4] = "R_rect: 1 0 0 0 1 0 0 0 1";
	lines[5] = "Tr_velo_cam: 0 -1 0 0.1 0 0 -1 -0.07 1 0 0 -0.3";
	lines[6] = "Tr_imu_velo: 1 0 0 -0.8 0 1 0 0.3 0 0 1 -0.9";
	kitti_test::writeLines(d + "/calib/0007.txt", lines);
	EXPECT_EQ(readCalib(d + "/calib/0007.txt").Tr_velo_to_cam(1, 2), -1);
}

TEST(KittiDetections, CountsPerClassAndFrameWithTheThreshold)
{
	// Car: frame 0 two boxes (scores 5, -0.5), frame 2 three (4, 3, 2); Cyclist: frame 1 one
	const std::string d = writeSet("det_count",
	                               {det(0, 2, 5, -3, 10), det(0, 2, -0.5, 8, 30),
	                                det(2, 2, 4, 4, 7), det(2, 2, 3, 6, 20), det(2, 2, 2, -6, 25)},
	                               {det(1, 3, 1.5, 2, 12)});
	CKittiApp app;
	ASSERT_EQ(runApp(d, app, "detection_classes = Car Cyclist\ndetection_min_score = 2"), "");
	const auto& car = app.detection_summary.classes.at("Car");
	EXPECT_EQ(car.lines, 5u);
	EXPECT_EQ(car.kept, 4u);  // 5, 4, 3, 2 (>= 2)
	EXPECT_EQ(car.below_threshold, 1u);
	EXPECT_EQ(car.per_frame.size(), 12u);
	EXPECT_EQ(car.per_frame[0], 1u);
	EXPECT_EQ(car.per_frame[2], 3u);
	EXPECT_EQ(car.frames_with_detections, 2u);
	EXPECT_EQ(car.max_per_frame, 3u);
	EXPECT_EQ(car.max_frame, 2);
	const auto& cyc = app.detection_summary.classes.at("Cyclist");
	EXPECT_EQ(cyc.kept, 0u);  // 1.5 < 2
	EXPECT_EQ(cyc.below_threshold, 1u);
	expectContains(app.summary.toText(), "Car: 5 lines, kept 4, below threshold 1");
	// the threshold on both sides of a score: 2 kept at 2, not at 2.001
	CKittiApp app2;
	ASSERT_EQ(runApp(d, app2, "detection_min_score = 2.001"), "");
	EXPECT_EQ(app2.detection_summary.classes.at("Car").kept, 3u);
	EXPECT_EQ(app2.detection_summary.classes.count("Cyclist"), 0u);  // default classes: Car
	CKittiApp app3;                                                  // default: no threshold
	ASSERT_EQ(runApp(d, app3), "");
	EXPECT_EQ(app3.detection_summary.classes.at("Car").kept, 5u);
}

TEST(KittiDetections, BadLinesNameFileAndLine)
{
	const std::string good = det(0, 2, 5, -3, 10);
	bool wrote = true;
	expectContains(appError({good, "1,2,3,4,5"}, calibLines(), &wrote),
	               "det/Car/0007.txt:2: expected 15 comma-separated columns, found 5");
	EXPECT_FALSE(wrote);
	wrote = true;
	expectContains(appError({good, det(1, 2, 5, NAN, 10)}, calibLines(), &wrote),
	               "0007.txt:2: column 11: non-finite");
	EXPECT_FALSE(wrote);  // a NaN box: nothing written (detection mode writes the boxes)
	expectContains(appError({good, det(1, 2, NAN, 1, 10)}), "0007.txt:2: column 7: non-finite");
	expectContains(appError({good, "1,2,,4,5,6,7,1,1,1,1,1,1,1,1"}),
	               "0007.txt:2: column 3 is empty");
	expectContains(appError({det(1, 2, 5, 1, 10), "x" + good}), "0007.txt:2: column 1:");
	expectContains(appError({det(-1, 2, 5, 1, 10)}), "0007.txt:1: negative frame");
	expectContains(appError({det(1, 1, 5, 1, 10)}), "0007.txt:1: class 1 (Pedestrian) in the Car");
	expectContains(appError({det(1, 7, 5, 1, 10)}), "0007.txt:1: class 7: expected 1");
	expectContains(appError({"1,2,1,2,3,4,5,1.5,0,4,1,1,1,1,1"}),
	               "0007.txt:1: box size h, w, l must be > 0");
	// frame 12 of a 12-frame sequence (frames 0..11): beyond; frame 11 is fine
	expectContains(appError({good, det(12, 2, 5, 1, 10), good}, calibLines(), &wrote),
	               "det/Car/0007.txt:2: frame 12 is beyond the sequence: ");
	EXPECT_FALSE(wrote);
	EXPECT_EQ(appError({good, det(11, 2, 5, 1, 10)}), "");
}

TEST(KittiDetections, BadCalibrationNamesFileAndLine)
{
	const std::vector<std::string> cars = {det(0, 2, 5, -3, 10)};
	auto with = [&](size_t i, const std::string& text)
	{
		auto c = calibLines();
		c[i] = text;
		return c;
	};
	bool wrote = true;
	expectContains(appError(cars, with(4, "R0_rect: 1 0 0 0 1 0 0 0"), &wrote),
	               "calib/0007.txt:5: R0_rect: expected 9 numbers, found 8");
	EXPECT_FALSE(wrote);
	expectContains(appError(cars, with(2, "P2: 700 0 nan 45 0 700 180 0.2 0 0 1 0.003")),
	               "calib/0007.txt:3: column 3: non-finite");
	expectContains(appError(cars, with(4, "R0_rect: 1 0 0 0 2 0 0 0 1")),
	               "calib/0007.txt:5: R0_rect: the 3x3 block is not a rotation");
	// the tolerance |R^T R - I| <= 1e-3 on both sides: 1.0004^2 - 1 = 8.0e-4, 1.0006^2 - 1 = 1.2e-3
	EXPECT_EQ(appError(cars, with(4, "R0_rect: 1.0004 0 0 0 1 0 0 0 1")), "");
	expectContains(appError(cars, with(4, "R0_rect: 1.0006 0 0 0 1 0 0 0 1")),
	               "calib/0007.txt:5: R0_rect: the 3x3 block is not a rotation");
	expectContains(appError(cars, with(6, "Tr_imu_velo_x: 1 0 0 0 0 1 0 0 0 0 1 0")),
	               "calib/0007.txt:7: unknown calibration key 'Tr_imu_velo_x'");
	expectContains(appError(cars, with(6, "P0: 700 0 600 0 0 700 180 0 0 0 1 0")),
	               "calib/0007.txt:7: P0 given twice");
	expectContains(appError(cars, with(1, "P1 700 0 600 -380 0 700 180 0 0 0 1 0")),
	               "calib/0007.txt:2: expected 'KEY: numbers'");
	auto noP3 = calibLines();
	noP3.erase(noP3.begin() + 3);
	expectContains(appError(cars, noP3), "calib/0007.txt: no P3 line");
	// a missing class folder, detection file, calibration file
	const std::string d = writeSet("det_missing", cars);
	CKittiApp app2;
	expectContains(runApp(d, app2, "detection_classes = Car Pedestrian"),
	               "det/Pedestrian: folder not found");
	fs::remove(d + "/det/Cyclist/0007.txt");
	CKittiApp app4;
	expectContains(runApp(d, app4, "detection_classes = Cyclist"),
	               "det/Cyclist/0007.txt: file not found");
	fs::remove(d + "/calib/0007.txt");
	CKittiApp app;
	expectContains(runApp(d, app), "calib/0007.txt: file not found");
	EXPECT_FALSE(fs::exists(d + "/out"));
	CKittiApp app3;
	app3.calib_dir = "";
	app3.labels_dir = d + "/label_02";
	app3.poses_dir = d + "/poses";
	app3.sequence = "0007";
	app3.out_dir = d + "/out";
	app3.detections_dir = d + "/det";
	EXPECT_THROW(app3.run(), std::invalid_argument);
}

TEST(KittiDetections, OptionsAreStrict)
{
	auto loadError = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory ini("[KITTI_Import]\n" + text + "\n");
		TKittiOptions o;
		try
		{
			o.loadFromConfigFile(ini, "KITTI_Import");
		}
		catch (const std::invalid_argument& e)
		{
			return std::string(e.what());
		}
		return std::string();
	};
	expectContains(loadError("detection_classes = Car Bus"), "'Bus' is not Car");
	expectContains(loadError("detection_classes = Car Car"), "'Car' given twice");
	expectContains(loadError("detection_min_score = nan"), "detection_min_score");
	expectContains(loadError("detection_min_score = high"), "detection_min_score");
	expectContains(loadError("detection_min_scor = 1"), "detection_min_scor");
	EXPECT_EQ(loadError("detection_classes = Cyclist Pedestrian\ndetection_min_score = none"), "");
}
