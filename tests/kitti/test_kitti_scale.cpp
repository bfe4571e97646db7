/** pose_scale (issue 31, item 3): a synthetic sequence whose camera trajectory is 3 % longer
 * than the boxes' geometry. pose_scale = 1 keeps the trajectory (the diagnostic reads 1.03);
 * pose_scale = auto (the default) rescales the positions by 1 / 1.03 (the diagnostic then reads 1,
 * and the parked cars stand still in the world); a number scales by that number. */
#include <dynslam/kitti/CKittiApp.h>
#include <dynslam/kitti/CKittiOptions.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <sstream>

#include "mini_sequence.h"

using namespace dynslam::kitti;

namespace
{
/** 20 frames; the camera truly drives 1 m per frame along its z axis, the pose file says
 * `scale` m. Two parked cars at world (forward, left) = (30, 4) and (25, -5); a car driving
 * beside the ego at 2 m per frame. */
std::string writeScaled(const std::string& name, double scale)
{
	const std::string d = kitti_test::tempDir(name);
	std::vector<std::string> poses, labels;
	for (int k = 0; k < 20; ++k)
	{
		std::ostringstream p;
		p.precision(17);
		p << "1 0 0 0 0 1 0 0 0 0 1 " << scale * k;
		poses.push_back(p.str());
		labels.push_back(kitti_test::labelLine(k, 0, "Car", -4, 30.0 - k, -M_PI / 2));
		labels.push_back(kitti_test::labelLine(k, 1, "Van", 5, 25.0 - k, -M_PI / 2));
		labels.push_back(kitti_test::labelLine(k, 2, "Car", 4, 5.0 + k, -M_PI / 2));
	}
	kitti_test::writeLines(d + "/poses/0007.txt", poses);
	kitti_test::writeLines(d + "/label_02/0007.txt", labels);
	return d;
}

TImportResult importWith(const std::string& d, const std::string& poseScale)
{
	TKittiOptions o;
	mrpt::config::CConfigFileMemory ini("[KITTI_Import]\nnoise = none\nodometry_noise = none\n" +
	                                    (poseScale.empty() ? "" : "pose_scale = " + poseScale) +
	                                    "\n");
	o.loadFromConfigFile(ini, "KITTI_Import");
	return importFromFiles(d + "/label_02", d + "/poses", "0007", o.import);
}
}  // namespace

TEST(KittiScale, AutoRescalesTheTrajectoryToTheLabels)
{
	const std::string d = writeScaled("scale", 1.03);
	// pose_scale = 1 (config/kitti.ini): the trajectory as given; the diagnostic finds the 3 %
	const TImportResult keep = importWith(d, "1");
	EXPECT_NEAR(keep.summary.trajectory_scale, 1.03, 1e-12);
	EXPECT_EQ(keep.summary.pose_scale, 1);
	EXPECT_NEAR(keep.gt.ego[19].x(), 1.03 * 19, 1e-12);
	// the parked cars seem to move backwards by 3 % of the path: corner scatter > 0
	EXPECT_GT(keep.summary.static_corner_rms, 0.1);

	const TImportResult aut = importWith(d, "auto");
	EXPECT_TRUE(aut.summary.pose_scale_auto);
	EXPECT_NEAR(aut.summary.trajectory_scale_unscaled, 1.03, 1e-12);
	EXPECT_NEAR(aut.summary.pose_scale, 1 / 1.03, 1e-12);
	EXPECT_NEAR(aut.summary.trajectory_scale, 1, 1e-12);
	EXPECT_NEAR(aut.summary.path_length, 19, 1e-9);  // the true path
	for (size_t k = 0; k < 20; ++k) EXPECT_NEAR(aut.gt.ego[k].x(), double(k), 1e-9) << k;
	EXPECT_LT(aut.summary.static_corner_rms, 1e-9);  // the parked cars stand still now
	// the odometry increments are the rescaled ones (noise off): 1 m per step
	EXPECT_NEAR(aut.steps[5].increment.x(), 1, 1e-12);
	// the box readings (the labels' geometry) are not touched
	ASSERT_EQ(aut.steps[7].readings.size(), keep.steps[7].readings.size());
	for (size_t i = 0; i < aut.steps[7].readings.size(); ++i)
		EXPECT_EQ(aut.steps[7].readings[i].range, keep.steps[7].readings[i].range);
	EXPECT_NE(aut.summary.toText().find("pose_scale = auto"), std::string::npos);
	// auto is the default (issue 31: the ground truth consistent unless an INI says otherwise)
	const TImportResult dflt = importWith(d, "");
	EXPECT_TRUE(dflt.summary.pose_scale_auto);
	EXPECT_EQ(dflt.gt.ego[19].x(), aut.gt.ego[19].x());

	// a number scales by it (1.05: the parked cars then drift 1.5 m, still static)
	const TImportResult more = importWith(d, "1.05");
	EXPECT_NEAR(more.gt.ego[19].x(), 1.05 * 1.03 * 19, 1e-9);
	EXPECT_NEAR(more.summary.trajectory_scale, 1.05 * 1.03, 1e-12);
	EXPECT_EQ(more.summary.static_tracks, 2u);
}

TEST(KittiScale, AutoWithoutStaticTracksKeepsTheTrajectory)
{
	// the mini sequence has no static track of >= 10 frames: the fit is NaN, the factor 1
	const std::string d = kitti_test::writeMiniSequence("scale_none", 12);
	const TImportResult r = importWith(d, "auto");
	EXPECT_TRUE(std::isnan(r.summary.trajectory_scale_unscaled));
	EXPECT_EQ(r.summary.pose_scale, 1);
	EXPECT_EQ(r.gt.ego[11].x(), 11);
}

TEST(KittiScale, BadValues)
{
	const std::string d = writeScaled("scale_bad", 1.0);
	for (const char* v : {"0", "-1", "nan", "Auto", "1.0x"})
	{
		EXPECT_THROW(importWith(d, v), std::invalid_argument) << v;
	}
	TImportOptions o;
	o.pose_scale = 0;
	EXPECT_THROW(importFromFiles(d + "/label_02", d + "/poses", "0007", o), std::invalid_argument);
}
