/** The synthetic detector (detection_simulator.h; issue 31 item 7) on the shipped excerpt's
 * labels (datasets/kitti, sequence 0000, frames 0-99): without misses, jitter or false positives
 * the imported boxes are the labels' boxes (ego frame, 1e-9); the writer's lines read back
 * exactly; misses, false positives, jitter and flips at their configured rates (bounds of 5
 * standard errors); bad options and command lines are clear errors. */
#include <dynslam/common/detection_boxes.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/CKittiApp.h>
#include <dynslam/kitti/detection_simulator.h>
#include <dynslam/kitti/geometry.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CRawlog.h>

#include <cmath>
#include <filesystem>

#include "detection_fixture.h"

using namespace dynslam;
using namespace dynslam::kitti;
namespace fs = std::filesystem;

namespace
{
const std::string kData = std::string(DYNSLAM_DATASETS_DIR) + "/kitti";

TKittiLabels excerptLabels() { return readLabels(kData + "/label_02/0000.txt"); }

bool detectable(const TKittiBox& b)
{
	return b.type == "Car" || b.type == "Pedestrian" || b.type == "Cyclist";
}

/** dynslam-kitti --simulate-detections on the excerpt with `ini` ([KITTI_Import] and
 * [KITTI_SimulateDetections] text); returns the output folder. */
std::string simulateAndImport(const std::string& name, const std::string& ini, CKittiApp& app)
{
	const std::string d = kitti_test::tempDir(name);
	mrpt::config::CConfigFileMemory c(ini);
	kitti_test::simulateAndImport(app, kData + "/label_02", kData + "/poses", d, c, c);
	return d;
}
}  // namespace

TEST(KittiSimulatedDetections, WithoutNoiseTheBoxesAreTheLabels)
{
	CKittiApp app;
	const std::string d = simulateAndImport(
	    "sim_exact",
	    "[KITTI_Import]\ndetection_classes = Car Pedestrian Cyclist\nmax_range = 1000\n", app);
	const TKittiLabels L = excerptLabels();
	mrpt::obs::CRawlog log;
	ASSERT_TRUE(log.loadFromRawLogFile(d + "/out/kitti_0000.rawlog"));
	ASSERT_EQ(log.size(), 200u);
	size_t boxes = 0, labelled = 0;
	for (size_t k = 0; k < 100; ++k)
	{
		const auto in = parseStepInput(log.getAsAction(2 * k), log.getAsObservations(2 * k + 1),
		                               TParseOptions(), "step");
		// the expected boxes: classes in the order of detection_classes, then label order
		std::vector<const TKittiBox*> want;
		for (const char* cls : {"Car", "Pedestrian", "Cyclist"})
			for (const auto& b : L.boxes)
				if (b.frame == int(k) && b.type == cls) want.push_back(&b);
		size_t perFrame = 0;
		for (const auto& [cls, c] : app.detection_summary.classes) perFrame += c.per_frame[k];
		ASSERT_EQ(in.boxes.size(), want.size()) << "frame " << k;
		EXPECT_EQ(in.boxes.size(), perFrame) << "boxes per frame = kept detections";
		ASSERT_EQ(in.readings.size(), 4 * want.size());
		for (size_t i = 0; i < want.size(); ++i)
		{
			const auto& b = in.boxes[i];
			const TKittiBox& l = *want[i];
			EXPECT_EQ(b.cls, l.type);
			EXPECT_LT((b.pose.head<2>() - boxCentreEgo(l)).norm(), 1e-9) << k << " " << i;
			EXPECT_LT(std::abs(models::wrapToPi(b.pose.z() - boxYawEgo(l.ry))), 1e-9);
			EXPECT_NEAR(b.extent.x(), l.l, 1e-9);
			EXPECT_NEAR(b.extent.y(), l.w, 1e-9);
			const auto corners = footprintCornersEgo(l);
			for (size_t j = 0; j < 4; ++j)  // the rawlog's corners: the label's footprint
				EXPECT_LT((in.readings[4 * i + j].z - corners.col(int(j))).norm(), 1e-4);
		}
		boxes += in.boxes.size();
		labelled += want.size();
	}
	size_t detectableBoxes = 0;
	for (const auto& b : L.boxes) detectableBoxes += detectable(b);
	EXPECT_EQ(boxes, detectableBoxes);  // nothing missed, nothing added
	EXPECT_GT(boxes, 100u);
	EXPECT_EQ(app.detection_summary.beyond_range, 0u);
	// max_range drops the far ones (the importer's filter, not the simulator's; the excerpt's
	// boxes, cyclists and pedestrians, all lie within 13 m, so 9 m here)
	CKittiApp near;
	simulateAndImport("sim_near",
	                  "[KITTI_Import]\ndetection_classes = Car Pedestrian Cyclist\nmax_range = 9\n",
	                  near);
	size_t within = 0;
	for (const auto& b : L.boxes) within += detectable(b) && boxCentreEgo(b).norm() <= 9;
	EXPECT_EQ(near.detection_summary.written, within);
	EXPECT_EQ(near.detection_summary.written + near.detection_summary.beyond_range, boxes);
	EXPECT_LT(within, boxes);
}

TEST(KittiSimulatedDetections, WrittenLinesReadBackExactly)
{
	TDetectionSimOptions o;
	o.std_xy = 0.3, o.std_yaw = 0.1, o.std_size = 0.2, o.false_positives_per_frame = 1.5;
	o.flip_probability = 0.2;
	const auto dets = simulateDetections(excerptLabels(), 100, o);
	const std::string d = kitti_test::tempDir("sim_lines");
	writeDetectionFiles(dets, d, "0000");
	size_t n = 0;
	for (const char* cls : {"Car", "Pedestrian", "Cyclist"})
	{
		const auto f = readDetections(d + "/" + cls + "/0000.txt", cls);
		for (const auto& r : f.detections)
		{
			const TKittiDetection* w = nullptr;
			for (const auto& x : dets)
				if (x.type == r.type && x.line == r.line) w = &x;
			ASSERT_NE(w, nullptr);
			EXPECT_EQ(r.frame, w->frame);
			EXPECT_EQ(r.score, w->score);
			EXPECT_EQ(r.h, w->h);
			EXPECT_EQ(r.w, w->w);
			EXPECT_EQ(r.l, w->l);
			EXPECT_EQ(r.x, w->x);
			EXPECT_EQ(r.y, w->y);
			EXPECT_EQ(r.z, w->z);
			EXPECT_EQ(r.ry, w->ry);
			EXPECT_EQ(r.alpha, w->alpha);
			++n;
		}
	}
	EXPECT_EQ(n, dets.size());
	writeNominalCalib(d + "/calib", "0000");
	EXPECT_NO_THROW(readCalib(d + "/calib/0000.txt"));
	// the same seed: the same detections; another seed: others
	EXPECT_EQ(detectionLine(simulateDetections(excerptLabels(), 100, o)[7]),
	          detectionLine(dets[7]));
	o.seed = 2;
	EXPECT_NE(detectionLine(simulateDetections(excerptLabels(), 100, o)[7]),
	          detectionLine(dets[7]));
}

TEST(KittiSimulatedDetections, RatesOfMissesFalsePositivesJitterAndFlips)
{
	const TKittiLabels L = excerptLabels();
	std::vector<const TKittiBox*> truth;
	for (const auto& b : L.boxes)
		if (detectable(b)) truth.push_back(&b);
	const double N = double(truth.size());
	// misses: binomial(N, 0.3)
	TDetectionSimOptions miss;
	miss.miss_probability = 0.3;
	const double kept = double(simulateDetections(L, 100, miss).size());
	EXPECT_NEAR(kept, 0.7 * N, 5 * std::sqrt(N * 0.3 * 0.7));
	// false positives: Poisson(2) per frame, 100 frames; in their sector, range, score range
	TDetectionSimOptions fp;
	fp.false_positives_per_frame = 2;
	const auto withFp = simulateDetections(L, 100, fp);
	const double nfp = double(withFp.size()) - N;
	EXPECT_NEAR(nfp, 200, 5 * std::sqrt(200.0));
	for (size_t i = 0; i < withFp.size(); ++i)
	{
		const auto& x = withFp[i];
		if (x.score >= fp.score_min) continue;  // a true detection (scores in [2, 10])
		const Eigen::Vector2d e = cameraToEgo(x.x, x.z);
		EXPECT_EQ(x.type, "Car");
		EXPECT_GE(e.norm(), fp.fp_min_range - 1e-9);
		EXPECT_LE(e.norm(), fp.fp_max_range + 1e-9);
		EXPECT_LE(std::abs(std::atan2(e.y(), e.x())), M_PI / 4 + 1e-12);
		EXPECT_GE(x.score, fp.fp_score_min);
		EXPECT_LE(x.score, fp.fp_score_max);
	}
	// jitter and flips (no misses: detection i is truth i)
	TDetectionSimOptions j;
	j.std_xy = 0.2, j.std_yaw = 0.05, j.std_size = 0.1, j.flip_probability = 0.25;
	const auto jit = simulateDetections(L, 100, j);
	ASSERT_EQ(jit.size(), truth.size());
	double sx = 0, sy = 0, ss = 0;
	size_t flips = 0;
	for (size_t i = 0; i < jit.size(); ++i)
	{
		sx += std::pow(jit[i].x - truth[i]->x, 2);
		ss += std::pow(jit[i].l - truth[i]->l, 2);
		double dy = models::wrapToPi(jit[i].ry - truth[i]->ry);
		if (std::abs(dy) > M_PI / 2)
		{
			++flips;
			dy = models::wrapToPi(dy + M_PI);
		}
		sy += dy * dy;
		EXPECT_GE(jit[i].score, j.score_min);
		EXPECT_LE(jit[i].score, j.score_max);
	}
	// sample std within 5 standard errors (std / sqrt(2N)) of the configured one
	const double rel = 5 / std::sqrt(2 * N);
	EXPECT_NEAR(std::sqrt(sx / N), 0.2, 0.2 * rel);
	EXPECT_NEAR(std::sqrt(sy / N), 0.05, 0.05 * rel);
	EXPECT_NEAR(std::sqrt(ss / N), 0.1, 0.1 * rel + 0.01);  // + the clamp at 0.1 m (none here)
	EXPECT_NEAR(double(flips), 0.25 * N, 5 * std::sqrt(N * 0.25 * 0.75));
}

TEST(KittiSimulatedDetections, BadOptionsAndCommandLines)
{
	auto loadError = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory ini("[KITTI_SimulateDetections]\n" + text + "\n");
		TKittiSimOptions o;
		try
		{
			o.loadFromConfigFile(ini, "KITTI_SimulateDetections");
		}
		catch (const std::invalid_argument& e)
		{
			return std::string(e.what());
		}
		return std::string();
	};
	EXPECT_EQ(loadError("miss_probability = 1\nflip_probability = 0"), "");
	EXPECT_NE(loadError("miss_probability = 1.01").find("miss_probability in [0, 1]"),
	          std::string::npos);
	EXPECT_NE(loadError("flip_probability = 2").find("flip_probability"), std::string::npos);
	EXPECT_NE(loadError("false_positives_per_frame = -1").find("false_positives_per_frame"),
	          std::string::npos);
	EXPECT_NE(loadError("fp_min_range = 50").find("fp_min_range <= fp_max_range"),
	          std::string::npos);
	EXPECT_NE(loadError("score_min = 3\nscore_max = 2").find("score_min <= score_max"),
	          std::string::npos);
	EXPECT_NE(loadError("std_xy = nan").find("std_xy"), std::string::npos);
	EXPECT_NE(loadError("miss_prob = 0.1").find("miss_prob"), std::string::npos);
	// labels beyond the frames simulated
	EXPECT_THROW(simulateDetections(excerptLabels(), 99, {}), std::invalid_argument);
	// --simulate-detections with --detections
	CKittiApp app;
	app.detections_dir = "x";
	app.calib_dir = "y";
	EXPECT_THROW(simulateAndImport("sim_both", "[KITTI_Import]\n", app), std::invalid_argument);
	// a malformed label line: the error names the file and line, nothing is written
	auto labels = kitti_test::miniLabels();
	labels[4] = "1 0 Car 0 0 -1.5 100 150 300 250 1.5 1.8 4 nan 1.6 9 0";  // NaN x
	const std::string d = kitti_test::writeMiniSequence("sim_badlabel", 12, labels);
	CKittiApp bad;
	bad.labels_dir = d + "/label_02";
	bad.poses_dir = d + "/poses";
	bad.sequence = "0007";
	bad.out_dir = d + "/out";
	bad.simulate_dir = d + "/det";
	try
	{
		bad.run();
		ADD_FAILURE() << "accepted";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("label_02/0007.txt:5:"), std::string::npos)
		    << e.what();
	}
	EXPECT_FALSE(fs::exists(d + "/det"));
	EXPECT_FALSE(fs::exists(d + "/out"));
}
