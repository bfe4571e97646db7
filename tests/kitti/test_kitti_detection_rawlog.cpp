/** Detection mode of dynslam-kitti (detection_import.h; issue 31 item 3): hand-written
 * detections become the rawlog's boxes (DETECTION_BOXES) and their corners the only readings
 * (ID -1), read back through the one step parser; the max_range filter on both sides of its
 * boundary; the labels' ground truth is still written (with the new _gt_boxes.csv), the
 * per-reading class truth is not. */
#include <dynslam/common/app_support.h>
#include <dynslam/common/detection_boxes.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/detection_import.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <cmath>
#include <fstream>

#include "detection_fixture.h"

using namespace dynslam;
using namespace dynslam::kitti;
using namespace kitti_test;

namespace
{
std::vector<estimator::TStepInput> readBack(const std::string& path)
{
	mrpt::obs::CRawlog log;
	EXPECT_TRUE(log.loadFromRawLogFile(path));
	std::vector<estimator::TStepInput> in;
	for (size_t k = 0; 2 * k + 1 < log.size(); ++k)
		in.push_back(parseStepInput(log.getAsAction(2 * k), log.getAsObservations(2 * k + 1),
		                            TParseOptions(), "step " + std::to_string(k)));
	return in;
}

std::vector<std::string> lines(const std::string& path)
{
	std::ifstream f(path);
	std::vector<std::string> v;
	for (std::string s; std::getline(f, s);) v.push_back(s);
	return v;
}
}  // namespace

TEST(KittiDetectionRawlog, BoxesAreTheReadings)
{
	// Car: frame 0 two; frame 2 three, two on either side of max_range = 40 (centre range
	// 39.99 and 40.01: ego (z, -x)); Cyclist: frame 1 one
	const std::string d =
	    writeSet("det_rawlog",
	             {det(0, 2, 5, -3, 10), det(0, 2, -0.5, 8, 30, 0.25), det(2, 2, 4, 4, 7),
	              det(2, 2, 3, 0, 39.99), det(2, 2, 2, 0, 40.01)},
	             {det(1, 3, 1.5, 2, 12)});
	CKittiApp app;
	ASSERT_EQ(runApp(d, app, "detection_classes = Car Cyclist\nnoise = gaussian"), "");
	EXPECT_EQ(app.detection_summary.written, 5u);
	EXPECT_EQ(app.detection_summary.beyond_range, 1u);
	EXPECT_EQ(app.detection_summary.frames_written, 3u);
	const auto in = readBack(d + "/out/kitti_0007.rawlog");
	ASSERT_EQ(in.size(), 12u);
	const size_t want[12] = {2, 1, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0};
	for (size_t k = 0; k < 12; ++k)
	{
		ASSERT_EQ(in[k].boxes.size(), want[k]) << k;
		ASSERT_EQ(in[k].readings.size(), 4 * want[k]) << "only the boxes' corners, step " << k;
		for (size_t i = 0; i < in[k].boxes.size(); ++i)
		{
			const auto c = boxCorners(in[k].boxes[i]);
			for (size_t j = 0; j < 4; ++j)
			{
				const auto& r = in[k].readings[4 * i + j];
				EXPECT_EQ(r.id, -1);
				EXPECT_EQ(r.hint, in[k].boxes[i].group);
				EXPECT_LT((r.z - c[j]).norm(), 1e-5 * c[j].norm()) << "float range and bearing";
			}
		}
	}
	// by hand: camera (x, z) = (-3, 10), rot_y = -1.5 -> ego (10, 3), yaw 1.5 - pi/2
	const auto& a = in[0].boxes[0];
	EXPECT_EQ(a.group, 0);
	EXPECT_EQ(a.cls, "Car");
	EXPECT_EQ(a.score, 5);
	EXPECT_EQ(a.pose.x(), 10);
	EXPECT_EQ(a.pose.y(), 3);
	EXPECT_NEAR(a.pose.z(), 1.5 - M_PI / 2, 1e-15);
	EXPECT_EQ(a.extent, Eigen::Vector2d(4.1, 1.7));
	// rot_y = 0.25 -> yaw -0.25 - pi/2; the score below 0 is kept (no threshold)
	EXPECT_NEAR(in[0].boxes[1].pose.z(), -0.25 - M_PI / 2, 1e-15);
	EXPECT_EQ(in[0].boxes[1].score, -0.5);
	EXPECT_EQ(in[1].boxes[0].cls, "Cyclist");
	EXPECT_EQ(in[1].boxes[0].group, 2);
	EXPECT_EQ(in[2].boxes[1].pose.x(), 39.99);  // inside max_range; 40.01 is not written
	EXPECT_EQ(in[2].boxes[1].group, 4);
	// the odometry as in the annotation mode
	EXPECT_NEAR(in[5].u.x(), 1, 0.2);

	// ground truth from the labels: the MOT truth per annotated box, world frame
	EXPECT_FALSE(fs::exists(d + "/out/kitti_0007_gt_classes.csv"));
	const auto gb = lines(d + "/out/kitti_0007_gt_boxes.csv");
	ASSERT_EQ(gb.size(), 1u + 9 + 12 + 12);  // parked car 9 frames, car 12, pedestrian 12
	EXPECT_EQ(gb[0], "step,t,track,type,moving,read,x,y,yaw,length,width");
	// track 1 at frame 3: camera (4, 5 + 3), ego (3, 0, 0): world (11, -4), yaw 0, moving, read
	std::string row;
	for (const auto& l : gb)
		if (l.rfind("3,", 0) == 0 && l.find(",1,Car,") != std::string::npos) row = l;
	EXPECT_EQ(row, "3,0.30000000000000004,1,Car,1,1,11,-4,0,4,1.8");
	bool detMode = false;
	for (const auto& l : lines(d + "/out/kitti_0007_scenario.ini"))
		detMode |= l == "mode = detections";
	EXPECT_TRUE(detMode);
}

TEST(KittiDetectionRawlog, WithoutDetectionsTheRawlogIsUnchanged)
{
	const std::string d = writeSet("det_none", {det(0, 2, 5, -3, 10)});
	CKittiApp app;
	app.labels_dir = d + "/label_02";
	app.poses_dir = d + "/poses";
	app.sequence = "0007";
	app.out_dir = d + "/out";
	app.run();
	const auto in = readBack(d + "/out/kitti_0007.rawlog");
	ASSERT_EQ(in.size(), 12u);
	EXPECT_TRUE(in[0].boxes.empty());
	EXPECT_EQ(in[0].readings.size(), 8u);  // the two annotated cars in view
	EXPECT_GE(in[0].readings[0].id, 0);
	EXPECT_TRUE(fs::exists(d + "/out/kitti_0007_gt_classes.csv"));
	EXPECT_TRUE(fs::exists(d + "/out/kitti_0007_gt_boxes.csv"));
}

TEST(KittiDetectionRawlog, ShippedDetectionIni)
{
	TKittiOptions det, ann;
	loadSectionOfFile(std::string(DYNSLAM_CONFIG_DIR) + "/kitti_detections.ini", "KITTI_Import",
	                  det);
	loadSectionOfFile(std::string(DYNSLAM_CONFIG_DIR) + "/kitti.ini", "KITTI_Import", ann);
	EXPECT_TRUE(det.import.pose_scale_auto);
	EXPECT_FALSE(ann.import.pose_scale_auto);
	EXPECT_EQ(det.detections.classes, std::vector<std::string>{"Car"});
	EXPECT_EQ(det.detections.min_score, -std::numeric_limits<double>::infinity());
	// the same steps and odometry as the annotation protocol
	EXPECT_EQ(det.import.dt, ann.import.dt);
	EXPECT_EQ(det.import.max_range, ann.import.max_range);
	EXPECT_EQ(det.import.odometry_noise, ann.import.odometry_noise);
	EXPECT_EQ(det.import.odo_std_xy, ann.import.odo_std_xy);
	EXPECT_EQ(det.import.odo_std_xy_per_m, ann.import.odo_std_xy_per_m);
	EXPECT_EQ(det.import.odo_std_phi, ann.import.odo_std_phi);
	EXPECT_EQ(det.import.odo_std_phi_per_m, ann.import.odo_std_phi_per_m);
	EXPECT_EQ(det.import.seed, ann.import.seed);
	EXPECT_EQ(det.import.static_radius, ann.import.static_radius);
}
