/** End to end with a detector's boxes (issue 31): a synthetic KITTI sequence (60 frames, the
 * camera driving 1 m per frame; eight parked cars beside the road, a car ahead in the ego's lane
 * and an oncoming one), boxes from the synthetic detector (dynslam-kitti --simulate-detections:
 * seeded misses, low-score false positives, jitter, front/back flips), imported with
 * config/kitti_detections.ini, then dynslam-compare with config/compare_kitti_detections.ini:
 * odometry, tracker_baseline and default. Thresholds a few times the measured values (printed;
 * doc/boxes.md). */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/kitti/CKittiApp.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <fstream>

#include "detection_fixture.h"

using namespace dynslam;

namespace
{
/** Writes the sequence's labels and poses into d (label_02/0000.txt, poses/0000.txt). */
void writeSequence(const std::string& d)
{
	const int frames = 60;
	std::ofstream labels(d + "/label_02/0000.txt"), poses(d + "/poses/0000.txt");
	for (int k = 0; k < frames; ++k)
	{
		poses << kitti_test::poseLine(k) << "\n";
		// Camera frame: x right, z forward; the length axis along z is rot_y = -pi/2.
		const auto box = [&](int track, double x, double zWorld, double ry)
		{
			const double z = zWorld - k;
			if (z > 2 && z < 45) labels << kitti_test::labelLine(k, track, "Car", x, z, ry) << "\n";
		};
		for (int i = 0; i < 8; ++i) box(i, i % 2 ? 4.5 : -4.5, 8.0 + 9.0 * i, -M_PI / 2);
		box(8, 0.0, 10.0 + 1.5 * k, -M_PI / 2);  // ahead in the ego's lane, faster
		box(9, -2.5, 70.0 - 1.5 * k, M_PI / 2);  // oncoming
	}
}

struct TRun
{
	std::vector<eval::TMetricsRow> rows;
	const eval::TMetricsRow& row(const std::string& f) const
	{
		for (const auto& r : rows)
			if (r.filter == f) return r;
		throw std::runtime_error("no row " + f);
	}
};

TRun runAll()
{
	const std::string d = kitti_test::tempDir("detections_e2e");
	writeSequence(d);
	kitti::CKittiApp imp;
	mrpt::config::CConfigFile ini(std::string(DYNSLAM_CONFIG_DIR) + "/kitti_detections.ini");
	mrpt::config::CConfigFileMemory sim(
	    "[KITTI_SimulateDetections]\nseed = 31\nmiss_probability = 0.1\n"
	    "false_positives_per_frame = 1\nfp_score_min = -1\nfp_score_max = 3\nscore_min = 6\n"
	    "score_max = 12\nstd_xy = 0.15\nstd_yaw = 0.05\nstd_size = 0.05\nflip_probability = 0.2\n");
	kitti_test::simulateAndImport(imp, d + "/label_02", d + "/poses", d, ini, sim);

	apps::CCompareApp app;
	std::vector<std::string> args{"dynslam-compare",
	                              "-c",
	                              std::string(DYNSLAM_CONFIG_DIR) + "/compare_kitti_detections.ini",
	                              "-r",
	                              d + "/out/kitti_0000.rawlog",
	                              "--filters",
	                              "odometry,tracker_baseline,default",
	                              "--no-figures",
	                              "-q"};
	std::vector<const char*> argv;
	for (const auto& a : args) argv.push_back(a.c_str());
	if (!app.initialize(int(argv.size()), argv.data())) throw std::runtime_error("initialize");
	app.run();
	return {app.rows};
}

const TRun& result()
{
	static const TRun r = runAll();
	return r;
}
}  // namespace

TEST(KittiDetectionsEndToEnd, RowsAndTrackingMetrics)
{
	const TRun& r = result();
	ASSERT_EQ(r.rows.size(), 3u);
	const auto& odo = r.row("odometry");
	const auto& base = r.row("tracker_baseline");
	const auto& def = r.row("default");
	EXPECT_FALSE(odo.mot.has_value());  // tracks no boxes
	ASSERT_TRUE(base.mot.has_value());
	ASSERT_TRUE(def.mot.has_value());
	for (const auto* x : {&base, &def})
		std::cout << x->filter << ": MOTA " << x->mot->iou.mota << " MOTP " << x->mot->iou.motp
		          << " IDS " << x->mot->iou.ids << " FP " << x->mot->iou.fp << " FN "
		          << x->mot->iou.fn << " of " << x->mot->iou.gt << ", sAMOTA " << x->mot->samota
		          << ", ATE " << x->metrics.ate << "\n";
	std::cout << "odometry ATE " << odo.metrics.ate << "\n";
	EXPECT_EQ(def.mot->cls, "Car");
	EXPECT_EQ(def.mot->iou.gt, base.mot->iou.gt);  // the same truth
	EXPECT_GT(def.mot->iou.gt, 250u);              // 278 annotated boxes in the region
	// Measured (2026-11-29): default MOTA 0.939 (FP 2, FN 15, IDS 0), tracker_baseline 0.953
	// (FP 0, FN 13): thresholds at about three times their error. The ~60 false positives
	// (scores below min_score 5) never become tracks.
	EXPECT_GT(def.mot->iou.mota, 0.82);
	EXPECT_GT(base.mot->iou.mota, 0.85);
	EXPECT_LE(def.mot->iou.fp, 10u);
	EXPECT_LE(def.mot->iou.ids, 2u);
}

TEST(KittiDetectionsEndToEnd, TheFilterBeatsDeadReckoningAndIsConsistent)
{
	const TRun& r = result();
	const auto& odo = r.row("odometry");
	const auto& def = r.row("default");
	EXPECT_LT(def.metrics.ate, odo.metrics.ate);
	EXPECT_DOUBLE_EQ(r.row("tracker_baseline").metrics.ate, odo.metrics.ate);  // same ego
	ASSERT_TRUE(def.consistency.has_value());
	std::cout << "default ego ANEES " << def.consistency->ego.anees << "\n";
	EXPECT_LT(def.consistency->ego.anees, 10.0);
}
