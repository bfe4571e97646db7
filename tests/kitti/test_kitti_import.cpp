/** Units of the KITTI importer: frame conversion, footprint corners, the classification rule,
 * IDs of both modes, noise, ground truth, options (libs/kitti). */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/CKittiOptions.h>
#include <dynslam/kitti/classify.h>
#include <dynslam/kitti/geometry.h>
#include <dynslam/kitti/import.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "mini_sequence.h"

using namespace dynslam;
using namespace dynslam::kitti;

namespace
{
/** Rotation about the camera's y axis by a (KITTI's R_y). */
TCameraPose cameraPose(double a, const Eigen::Vector3d& t)
{
	TCameraPose T;
	T << std::cos(a), 0, std::sin(a), t.x(), 0, 1, 0, t.y(), -std::sin(a), 0, std::cos(a), t.z();
	return T;
}

TImportResult importMini(TImportOptions o, int frames = 12)
{
	const std::string d = kitti_test::writeMiniSequence("units", frames);
	const auto poses = readPoses(d + "/poses/0007.txt");
	const auto labels = readLabels(d + "/label_02/0007.txt");
	return importSequence(poses, labels, o, "0007");
}

TImportOptions noiseless()
{
	TImportOptions o;
	o.noise = ENoise::None;
	o.odometry_noise = ENoise::None;
	return o;
}
}  // namespace

TEST(KittiGeometry, EgoPoseFromCamera)
{
	// the camera at (x, y, z) = (2, -1, 5) is the ego at (5, -2); heading = -rotation about y
	for (double a : {0.0, 0.3, -1.2, 2.9})
	{
		const Eigen::Vector3d p = egoPoseFromCamera(cameraPose(a, {2, -1, 5}));
		EXPECT_NEAR(p.x(), 5, 1e-15);
		EXPECT_NEAR(p.y(), -2, 1e-15);
		EXPECT_NEAR(models::wrapToPi(p.z() + a), 0, 1e-12) << a;
	}
	// turning right (camera z towards camera x = right) is a negative heading
	EXPECT_NEAR(egoPoseFromCamera(cameraPose(M_PI / 2, {0, 0, 0})).z(), -M_PI / 2, 1e-12);
	// a camera-frame point maps to the ego frame consistently with the pose: the world point of
	// camera point (x, 0, z) is R p + t; its 2-D image equals ego (+) (z, -x)
	const TCameraPose T = cameraPose(0.7, {1, 0, 3});
	const Eigen::Vector3d pw = T.leftCols<3>() * Eigen::Vector3d(1.5, 0, 8) + T.col(3);
	const Eigen::Vector2d viaEgo = egoToWorld(egoPoseFromCamera(T), cameraToEgo(1.5, 8));
	EXPECT_NEAR(viaEgo.x(), pw.z(), 1e-12);
	EXPECT_NEAR(viaEgo.y(), -pw.x(), 1e-12);
}

TEST(KittiGeometry, FootprintCornersMatchKittisBoxFormula)
{
	// KITTI's own corners: R_y(ry) (xo, 0, zo) + (x, y, z), xo = +-l/2, zo = +-w/2 (devkit's
	// compute_box_3d), mapped to the ego frame as (z, -x).
	std::mt19937 rng(5);
	std::uniform_real_distribution<double> U(-3, 3);
	for (int trial = 0; trial < 20; ++trial)
	{
		TKittiBox b;
		b.x = 3 * U(rng);
		b.z = 10 + 3 * U(rng);
		b.ry = U(rng);
		b.l = 4 + U(rng) / 3;
		b.w = 1.8 + U(rng) / 10;
		const auto c = footprintCornersEgo(b);
		const double xo[4] = {b.l / 2, b.l / 2, -b.l / 2, -b.l / 2};
		const double zo[4] = {b.w / 2, -b.w / 2, -b.w / 2, b.w / 2};
		for (int j = 0; j < 4; ++j)
		{
			const double xc = std::cos(b.ry) * xo[j] + std::sin(b.ry) * zo[j] + b.x;
			const double zc = -std::sin(b.ry) * xo[j] + std::cos(b.ry) * zo[j] + b.z;
			EXPECT_NEAR(c(0, j), zc, 1e-12);
			EXPECT_NEAR(c(1, j), -xc, 1e-12);
		}
		EXPECT_NEAR((c.rowwise().mean() - boxCentreEgo(b)).norm(), 0, 1e-12);
	}
	// ry = -pi/2: the length along the camera's z axis (forward); corner order front-left first
	TKittiBox b;
	b.x = -3;
	b.z = 10;
	b.ry = -M_PI / 2;
	b.l = 4;
	b.w = 1.8;
	Eigen::Matrix<double, 2, 4> expected;
	expected << 12, 12, 8, 8, 3.9, 2.1, 2.1, 3.9;
	EXPECT_LT((footprintCornersEgo(b) - expected).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_NEAR(boxYawEgo(-M_PI / 2), 0, 1e-15);
}

TEST(KittiClassify, RadiusRule)
{
	EXPECT_EQ(footprintRadius({}), 0);
	EXPECT_EQ(footprintRadius({Eigen::Vector2d(3, 4)}), 0);
	// mean (1, 0): the farthest point is 1 m away
	EXPECT_NEAR(footprintRadius({{0, 0}, {2, 0}, {1, 0}}), 1.0, 1e-15);
	EXPECT_NEAR(footprintRadius({{0, 0}, {0, 0}, {0, 0}, {4, 0}}), 3.0, 1e-15);
	EXPECT_FALSE(isMoving(2.0, 2.0));
	EXPECT_TRUE(isMoving(2.0001, 2.0));
	// on the mini sequence: the parked car stays put (radius 0), the other drives 20 m
	const TImportResult r = importMini(noiseless());
	EXPECT_FALSE(r.tracks.at(0).moving);
	EXPECT_NEAR(r.tracks.at(0).radius, 0, 1e-9);
	EXPECT_TRUE(r.tracks.at(1).moving);
	EXPECT_NEAR(r.tracks.at(1).radius, 11, 1e-9);
	// the rule is about motion, not type: a threshold above 11 m makes the driving car static
	TImportOptions o = noiseless();
	o.static_radius = 11.5;
	EXPECT_FALSE(importMini(o).tracks.at(1).moving);
}

TEST(KittiImport, LabelledStepsIdsAndGroundTruth)
{
	const TImportResult r = importMini(noiseless());
	const auto& s = r.summary;
	EXPECT_EQ(s.steps, 12u);
	EXPECT_EQ(s.dontcare, 12u);
	EXPECT_EQ(s.out_of_fov, 12u + 1u);  // the pedestrian; the parked car at frame 8
	EXPECT_EQ(s.boxes_read, 8u + 12u);
	EXPECT_EQ(s.readings, 4 * s.boxes_read);
	ASSERT_EQ(r.steps.size(), 12u);
	EXPECT_EQ(r.steps[0].increment, Eigen::Vector3d::Zero());
	EXPECT_EQ(r.steps[0].cov, Eigen::Matrix3d::Zero());
	EXPECT_LT((r.steps[3].increment - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
	// cov = diag(s_xy^2, s_xy^2, s_phi^2), s_xy = 0.01 + 0.02 * 1, s_phi = 0.002 + 0.001 * 1
	EXPECT_NEAR(r.steps[3].cov(0, 0), 0.03 * 0.03, 1e-15);
	EXPECT_NEAR(r.steps[3].cov(2, 2), 0.003 * 0.003, 1e-15);
	// step 2: parked car corners 0..3, moving car = object 0 features 0..3
	ASSERT_EQ(r.steps[2].readings.size(), 8u);
	std::set<int32_t> ids;
	for (const auto& z : r.steps[2].readings) ids.insert(z.id);
	const std::set<int32_t> expected{0,
	                                 1,
	                                 2,
	                                 3,
	                                 ids::objectFeatureId(0, 0),
	                                 ids::objectFeatureId(0, 1),
	                                 ids::objectFeatureId(0, 2),
	                                 ids::objectFeatureId(0, 3)};
	EXPECT_EQ(ids, expected);
	// reading of corner 0 (front-left) of the parked car at step 2: ego (2, 0), corner (12, 3.9)
	const auto& z0 = r.steps[2].readings[0];
	EXPECT_EQ(z0.id, 0);
	EXPECT_NEAR(z0.range, std::hypot(10.0, 3.9), 1e-12);
	EXPECT_NEAR(z0.bearing, std::atan2(3.9, 10.0), 1e-12);
	// ground truth: landmarks at their (constant) world position; object pose (2k, 0, 0)
	EXPECT_LT((r.gt.landmarks.at(0) - Eigen::Vector2d(12, 3.9)).norm(), 1e-12);
	EXPECT_LT((r.gt.landmarks.at(2) - Eigen::Vector2d(8, 2.1)).norm(), 1e-12);
	ASSERT_EQ(r.gt.objects.size(), 1u);
	const auto& o = r.gt.objects[0];
	EXPECT_EQ(o.first_step, 0);
	EXPECT_EQ(o.num_features, 4);
	EXPECT_LT((o.pose[5] - Eigen::Vector3d(10, 0, 0)).norm(), 1e-12);
	EXPECT_LT((o.features[5].col(0) - Eigen::Vector2d(17, -3.1)).norm(), 1e-12);
	EXPECT_EQ(o.visible[5], 1);
	EXPECT_EQ(r.gt.ego[7], Eigen::Vector3d(7, 0, 0));
	EXPECT_DOUBLE_EQ(r.gt.t[7], 0.7);
	// per-step class truth: every annotated (frame, track), the pedestrian unread
	EXPECT_EQ(r.track_steps.size(), 9u + 12u + 12u);
	for (const auto& row : r.track_steps)
	{
		EXPECT_EQ(row.moving, row.track != 0);
		EXPECT_EQ(row.read, row.track == 1 || (row.track == 0 && row.step < 8));
	}
	// jitter floor of noiseless, perfectly still boxes: zero
	EXPECT_EQ(s.floor_n, 7u);
	EXPECT_NEAR(s.floor_trans_rmse, 0, 1e-12);
	EXPECT_NEAR(s.static_corner_rms, 0, 1e-12);
}

TEST(KittiImport, AnonymousIdsSayNothingAndKeepTheReadings)
{
	TImportOptions o;  // gaussian noise: the same draws in both modes
	const TImportResult lab = importMini(o);
	o.anonymous = true;
	const TImportResult an = importMini(o);
	std::set<int32_t> all;
	ASSERT_EQ(an.steps.size(), lab.steps.size());
	for (size_t k = 0; k < an.steps.size(); ++k)
	{
		ASSERT_EQ(an.steps[k].readings.size(), lab.steps[k].readings.size());
		for (size_t i = 0; i < an.steps[k].readings.size(); ++i)
		{
			const auto& a = an.steps[k].readings[i];
			const auto& b = lab.steps[k].readings[i];
			EXPECT_EQ(a.range, b.range);
			EXPECT_EQ(a.bearing, b.bearing);
			EXPECT_EQ(a.track, b.track);
			EXPECT_TRUE(ids::isStatic(a.id));  // no ID range tells moving from static
			all.insert(a.id);
		}
	}
	// IDs 0..N-1, N = 8 read corners; the table maps each back to its track and corner
	EXPECT_EQ(all, std::set<int32_t>({0, 1, 2, 3, 4, 5, 6, 7}));
	ASSERT_EQ(an.ids.size(), 8u);
	std::vector<int32_t> order;
	for (const auto& row : an.ids) order.push_back(row.track * 4 + row.corner);
	EXPECT_NE(order,
	          std::vector<int32_t>({0, 1, 2, 3, 4, 5, 6, 7}));  // a permutation, not the identity
	for (const auto& row : an.ids)
		if (!row.moving)
		{
			EXPECT_TRUE(an.gt.landmarks.count(row.id));
		}
	EXPECT_EQ(an.gt.landmarks.size(), 4u);
	EXPECT_EQ(an.gt.objects.size(), 1u);
}

TEST(KittiImport, SeededNoiseWithTheConfiguredSpread)
{
	// the shipped excerpt is not needed here: 200 frames of the mini layout
	std::vector<std::string> labels;
	for (int k = 0; k < 200; ++k)
		labels.push_back(kitti_test::labelLine(k, 1, "Car", 4, 5.0 + k, -M_PI / 2));
	const std::string d = kitti_test::writeMiniSequence("noise", 200, labels);
	const auto poses = readPoses(d + "/poses/0007.txt");
	const auto L = readLabels(d + "/label_02/0007.txt");
	TImportOptions o;
	const auto a = importSequence(poses, L, o, "0007");
	const auto b = importSequence(poses, L, o, "0007");
	const auto exact = importSequence(poses, L, noiseless(), "0007");
	o.seed = 2;
	const auto c = importSequence(poses, L, o, "0007");
	double sr = 0, sb = 0, so = 0;
	size_t n = 0;
	for (size_t k = 1; k < a.steps.size(); ++k)
	{
		EXPECT_EQ(a.steps[k].increment, b.steps[k].increment);
		EXPECT_NE(a.steps[k].increment, c.steps[k].increment);
		so += (a.steps[k].increment.x() - 1) / std::sqrt(a.steps[k].cov(0, 0));
		for (size_t i = 0; i < a.steps[k].readings.size(); ++i, ++n)
		{
			sr += std::pow(a.steps[k].readings[i].range - exact.steps[k].readings[i].range, 2);
			sb += std::pow(a.steps[k].readings[i].bearing - exact.steps[k].readings[i].bearing, 2);
		}
	}
	// 796 draws each: the sample std within 10 % of the configured one (5 sigma ~ 12.5 %)
	EXPECT_NEAR(std::sqrt(sr / double(n)), o.std_range, 0.1 * o.std_range);
	EXPECT_NEAR(std::sqrt(sb / double(n)), o.std_bearing, 0.1 * o.std_bearing);
	EXPECT_LT(std::abs(so / 199), 0.4);  // normalized odometry error has mean ~ 0 (5 sigma)
}

TEST(KittiOptions, ShippedIniEqualsTheDefaults)
{
	mrpt::config::CConfigFile ini(std::string(DYNSLAM_CONFIG_DIR) + "/kitti.ini");
	TKittiOptions o;
	o.loadFromConfigFile(ini, "KITTI_Import");
	const TImportOptions d;
	const auto& i = o.import;
	EXPECT_EQ(i.dt, d.dt);
	EXPECT_EQ(i.max_range, d.max_range);
	EXPECT_EQ(i.fov_deg, d.fov_deg);
	EXPECT_EQ(i.static_radius, d.static_radius);
	EXPECT_EQ(i.noise, d.noise);
	EXPECT_EQ(i.odometry_noise, d.odometry_noise);
	EXPECT_EQ(i.seed, d.seed);
	EXPECT_EQ(i.std_range, d.std_range);
	EXPECT_EQ(i.std_bearing, d.std_bearing);
	EXPECT_EQ(i.odo_std_xy, d.odo_std_xy);
	EXPECT_EQ(i.odo_std_xy_per_m, d.odo_std_xy_per_m);
	EXPECT_EQ(i.odo_std_phi, d.odo_std_phi);
	EXPECT_EQ(i.odo_std_phi_per_m, d.odo_std_phi_per_m);
	EXPECT_EQ(i.detection_groups, d.detection_groups);
	// the one difference (issue 31): the code's default is pose_scale = auto, the annotation
	// protocol's INI pins 1 (its tables in doc/kitti.md section 5 were measured at scale 1)
	EXPECT_TRUE(d.pose_scale_auto);
	EXPECT_FALSE(i.pose_scale_auto);
	EXPECT_EQ(i.pose_scale, 1.0);
	const TDetectionOptions dd;
	EXPECT_EQ(o.detections.classes, dd.classes);
	EXPECT_EQ(o.detections.min_score, dd.min_score);
}

TEST(KittiOptions, BadValuesNameSectionAndKey)
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
	EXPECT_NE(loadError("max_rang = 30").find("max_rang"), std::string::npos);
	EXPECT_NE(loadError("noise = loud").find("noise"), std::string::npos);
	EXPECT_NE(loadError("static_radius = -1").find("static_radius"), std::string::npos);
	EXPECT_NE(loadError("fov_deg = 400").find("fov_deg"), std::string::npos);
	EXPECT_NE(loadError("std_range = nan").find("std_range"), std::string::npos);
	EXPECT_EQ(loadError("noise = none\nodometry_noise = none"), "");
}
