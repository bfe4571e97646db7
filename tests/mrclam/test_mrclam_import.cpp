/** The import rules on the synthetic mini data set: world frame, increments, time window,
 * duration, ground truth of the other robots. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/mrclam/import.h>
#include <gtest/gtest.h>

#include <cmath>

#include "mini_dataset.h"

using namespace dynslam::mrclam;
using namespace mrclam_test;

namespace
{
TImportOptions plainOptions()
{
	TImportOptions o;
	o.odometry_delay = 0;
	o.odometry_scale_v = 1;
	o.odometry_scale_w = 1;
	return o;
}
}  // namespace

TEST(MrclamImport, WorldFrameIncrementsAndObjects)
{
	// mini data set: robot r at (0.1 t, r, 0); commands v = 0.1, w = 0; steps at t = 1, 2, 3
	const auto d = loadDataset(writeMiniDataset("frame"), 1);
	const auto r = importRobot(d, plainOptions());
	ASSERT_EQ(r.steps.size(), 3u);
	EXPECT_NEAR((r.summary.origin - Eigen::Vector3d(0.1, 1.0, 0.0)).norm(), 0, 1e-12);
	// ego: (0.1 (t - 1), 0, 0) in the frame of its pose at step 0
	for (size_t k = 0; k < 3; k++)
		EXPECT_NEAR((r.gt.ego[k] - Eigen::Vector3d(0.1 * k, 0, 0)).norm(), 0, 1e-12);
	// landmark 6 at (3, 1) -> (2.9, 0)
	EXPECT_NEAR((r.gt.landmarks.at(6) - Eigen::Vector2d(2.9, 0)).norm(), 0, 1e-12);
	// increments: zero first, then 0.1 m straight ahead, covariance from the model
	EXPECT_EQ(r.steps[0].increment.delta.norm(), 0.0);
	EXPECT_EQ(r.steps[0].cov.norm(), 0.0);
	EXPECT_NEAR((r.steps[1].increment.delta - Eigen::Vector3d(0.1, 0, 0)).norm(), 0, 1e-12);
	EXPECT_NEAR(r.steps[1].increment.distance, 0.1, 1e-12);
	EXPECT_NEAR(
	    (r.steps[1].cov - plainOptions().odometry_noise.covariance(r.steps[1].increment)).norm(), 0,
	    1e-18);
	// robot 2 at (0.1 t, 2): object 2, measured at steps 0 and 2
	const auto& o = r.gt.objects.at(2);
	EXPECT_EQ(o.object, 2);
	EXPECT_EQ(o.first_step, 0);
	EXPECT_EQ(std::vector<uint8_t>(o.visible.begin(), o.visible.end()),
	          (std::vector<uint8_t>{1, 0, 1}));
	EXPECT_NEAR((o.features[2].col(0) - Eigen::Vector2d(0.2, 1.0)).norm(), 0, 1e-12);
	EXPECT_NEAR((o.pose[2] - Eigen::Vector3d(0.2, 0, 0)).norm(), 0, 1e-12);
	// robot 3 is never measured: first_step -1, pose NaN, position still exported
	EXPECT_EQ(r.gt.objects.at(3).first_step, -1);
	EXPECT_TRUE(std::isnan(r.gt.objects.at(3).pose[1].x()));
	EXPECT_TRUE(r.gt.objects.at(3).features[1].allFinite());
	// placeholders: object 0 and the ego
	EXPECT_FALSE(r.gt.objects.at(1).features[0].allFinite());
	EXPECT_FALSE(r.gt.objects.at(0).features[0].allFinite());
}

TEST(MrclamImport, DurationAndGroundTruthWindow)
{
	const auto dir = writeMiniDataset("window");
	auto opts = plainOptions();
	opts.duration = 1.5;  // steps at 1.0 and 2.0; the measurement at 3.0 is outside
	auto r = importRobot(loadDataset(dir, 1), opts);
	EXPECT_EQ(r.steps.size(), 2u);
	EXPECT_EQ(r.summary.outside_window, 1u);
	EXPECT_EQ(r.summary.kept, 3u);
	EXPECT_DOUBLE_EQ(r.summary.duration(), 1.0);
	// robot 4's Vicon record ends at 2.5 s: with clipping, the step at 3.0 is dropped
	std::string gt = kHeader;
	for (int i = 0; i <= 25; i++)
		gt += std::to_string(0.1 * i) + " " + std::to_string(0.01 * i) + " 4 0\n";
	writeFile(dir + "/Robot4_Groundtruth.dat", gt);
	r = importRobot(loadDataset(dir, 1), plainOptions());
	EXPECT_EQ(r.steps.size(), 2u);
	EXPECT_EQ(r.summary.outside_window, 1u);
	// without clipping it stays, and robot 4's position there is NaN (no extrapolation)
	opts = plainOptions();
	opts.clip_to_ground_truth = false;
	r = importRobot(loadDataset(dir, 1), opts);
	ASSERT_EQ(r.steps.size(), 3u);
	EXPECT_FALSE(r.gt.objects.at(4).features[2].allFinite());
	EXPECT_TRUE(r.gt.objects.at(4).features[1].allFinite());
}
