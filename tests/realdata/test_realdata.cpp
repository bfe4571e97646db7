/** End to end on real data: the shipped MRCLAM excerpt (Dataset 6, robot 3, 121 s, 313 steps,
 * converted by the build target mrclam_excerpt with config/mrclam.ini) through the three filters
 * of dynslam-compare with config/mrclam_compare.ini (doc/results/real-data.md, section 5.4).
 *
 * Thresholds come from the values measured on this excerpt (listed with each test and in the
 * doc) with a stated margin; they are not tuned to make the tests pass. Measured (Release,
 * MRPT 2.5.8): ego ATE static_all 0.320 m, static_landmarks_only 0.108 m, dynamic 0.108 m;
 * landmark RMSE 3.128 / 0.532 / 0.532 m; tracked robots (dynamic, 241 sightings) pooled RMSE
 * 0.275 m, per robot 0.277 (1), 0.126 (2), 0.421 (4), 0.256 (5) m; gate: 0 of 540 updates. */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/data_files.h>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>

#include "realdata_run.h"

using namespace dynslam;

namespace
{
const std::string kRawlog =
    std::string(DYNSLAM_BINARY_DIR) + "/datasets/mrclam/robot3_excerpt.rawlog";
const std::string kIni = std::string(DYNSLAM_CONFIG_DIR) + "/mrclam_compare.ini";

/** The four runs, computed once for all tests. */
struct TExcerpt
{
	apps::TRawlog rawlog;
	io::TGroundTruth gt;
	std::map<std::string, realdata::TRealDataResult> r;
};

const TExcerpt& excerpt()
{
	static const std::unique_ptr<TExcerpt> e = []
	{
		auto x = std::make_unique<TExcerpt>();
		x->rawlog = apps::loadRawlog(kRawlog);
		x->gt = apps::loadGroundTruthFor(apps::groundTruthBesideRawlog(kRawlog), x->rawlog.size(),
		                                 kRawlog);
		mrpt::config::CConfigFileMemory ini;
		apps::loadIniFile(kIni, ini);
		for (const std::string f : {"static_all", "static_landmarks_only", "dynamic",
		                            "dynamic_nogate", "dynamic_classified"})
			x->r[f] = realdata::runRealData(x->rawlog, x->gt, ini, f);
		return x;
	}();
	return *e;
}
}  // namespace

TEST(RealDataExcerpt, InputIsTheShippedExcerpt)
{
	const auto& e = excerpt();
	EXPECT_EQ(e.rawlog.size(), 313u);
	EXPECT_EQ(e.gt.landmarks.size(), 15u);
	for (const auto& [f, r] : e.r)
	{
		EXPECT_EQ(r.run.steps, 313u) << f;
		EXPECT_EQ(r.landmarks_scored, 15u) << f;  // every landmark is seen in the excerpt
	}
}

// Issue 7: "the dynamic EKF's ego ATE and landmark RMSE are no worse than the static filter
// that sees everything". Tolerance 0.02 m on both: about 1/8 of the range noise std (0.155 m),
// i.e. "equal" for practical purposes; measured margins are far larger (ATE 0.108 vs 0.320 m,
// landmarks 0.532 vs 3.128 m).
TEST(RealDataExcerpt, DynamicNoWorseThanStaticAll)
{
	const auto& e = excerpt();
	const auto& dyn = e.r.at("dynamic");
	const auto& all = e.r.at("static_all");
	EXPECT_LE(dyn.ate, all.ate + 0.02);
	EXPECT_LE(dyn.landmark_rmse, all.landmark_rmse + 0.02);
	EXPECT_TRUE(std::isfinite(dyn.ate) && std::isfinite(dyn.landmark_rmse));
}

// The dynamic EKF never uses a robot sighting to correct the ego or the map (Alg. 3-4 only
// augment): without the gate it must give the ego path of MRPT's filter fed the landmarks only
// (same data, same R, same odometry covariance). Measured: largest difference 3.8e-6 m / 1.8e-6 rad
// (rounding of two implementations); bound 1e-4 m / 1e-5 rad.
TEST(RealDataExcerpt, DynamicWithoutGateEqualsStaticLandmarksOnly)
{
	const auto& e = excerpt();
	const auto& a = e.r.at("dynamic_nogate").run.est.ego;
	const auto& b = e.r.at("static_landmarks_only").run.est.ego;
	ASSERT_EQ(a.size(), b.size());
	double dp = 0, dth = 0;
	for (size_t k = 0; k < a.size(); ++k)
	{
		dp = std::max(dp, (a[k].mean.head<2>() - b[k].mean.head<2>()).norm());
		dth = std::max(dth, std::abs(std::remainder(a[k].mean.z() - b[k].mean.z(), 2 * M_PI)));
	}
	std::cout << "largest ego difference: " << dp << " m, " << dth << " rad\n";
	EXPECT_LT(dp, 1e-4);
	EXPECT_LT(dth, 1e-5);
	EXPECT_NEAR(e.r.at("dynamic_nogate").landmark_rmse,
	            e.r.at("static_landmarks_only").landmark_rmse, 1e-4);
}

// Item 2: every other robot is a one-feature object with a translation-only pose (2-dof mean and
// 2x2 covariance); object 0 and the ego's own index (3) never get a track.
TEST(RealDataExcerpt, RobotsAreOneFeatureTranslationOnlyObjects)
{
	const auto& est = excerpt().r.at("dynamic").run.est;
	std::map<int, int> features, poses;
	for (const auto& f : est.object_features) ++features[f.object];
	for (const auto& p : est.object_poses)
	{
		++poses[p.object];
		EXPECT_EQ(p.mean.size(), 2) << "object " << p.object << " step " << p.step;
		EXPECT_EQ(p.cov.rows(), 2);
	}
	EXPECT_EQ(features, (std::map<int, int>{{1, 1}, {2, 1}, {4, 1}, {5, 1}}));
	for (int r : {1, 2, 4, 5}) EXPECT_GT(poses[r], 0) << "robot " << r;
	EXPECT_EQ(poses.count(0) + poses.count(3), 0u);
}

// The other robots are tracked: one online position estimate per sighting after the first (the
// first sighting initializes f_0), and position RMSE below thresholds = measured x ~1.5:
// pooled 0.40 m (measured 0.275 m), each robot 0.65 m (largest measured: robot 4, 0.421 m).
// Consistency of p_t: at least 90 % of the NEES values below chi2_2(0.95) (measured 97.9 %).
TEST(RealDataExcerpt, OtherRobotsTracked)
{
	const auto& e = excerpt();
	const auto& dyn = e.r.at("dynamic");
	size_t expected = 0;
	for (const auto& o : e.gt.objects)
	{
		if (o.first_step < 0) continue;  // placeholders (object 0, the ego)
		size_t seen = 0;
		for (size_t k = 0; k < o.visible.size(); ++k) seen += o.visible[k] && int(k) > o.first_step;
		ASSERT_TRUE(dyn.tracked_by_robot.count(o.object)) << "robot " << o.object;
		const auto& s = dyn.tracked_by_robot.at(o.object);
		EXPECT_EQ(s.n, seen) << "robot " << o.object;
		EXPECT_LT(s.rmse, 0.65) << "robot " << o.object;
		expected += seen;
	}
	EXPECT_EQ(dyn.tracked_by_robot.size(), 4u);
	EXPECT_EQ(dyn.tracked_all.n, expected);
	EXPECT_EQ(expected, 241u);  // 245 robot readings, 4 of them first sightings
	EXPECT_LT(dyn.tracked_all.rmse, 0.40);
	EXPECT_GE(dyn.tracked_all.frac_nees_in95, 0.90);
	// Only the dynamic filters track anything.
	EXPECT_TRUE(e.r.at("static_all").tracked.empty());
	EXPECT_TRUE(e.r.at("static_landmarks_only").tracked.empty());
}

// dynslam-compare itself (CCompareApp) with config/mrclam_compare.ini on the excerpt: four
// rows (issue 12 added dynamic_classified), and the same ATE as the runs above (same back-ends,
// same data).
TEST(RealDataExcerpt, CompareAppRunsTheConfig)
{
	apps::CCompareApp app;
	app.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const char* argv[] = {"dynslam-compare", "-c",           kIni.c_str(), "-r",
	                      kRawlog.c_str(),   "--no-figures", "-q"};
	ASSERT_TRUE(app.initialize(7, argv));
	app.run();
	ASSERT_TRUE(app.hasGroundTruth);
	ASSERT_EQ(app.rows.size(), 5u);
	EXPECT_EQ(app.rows[3].filter, "dynamic_classified");
	EXPECT_EQ(app.rows[4].filter, "default");
	const auto& e = excerpt();
	for (const auto& row : app.rows)
	{
		if (row.filter != "default")
		{
			EXPECT_NEAR(row.metrics.ate, e.r.at(row.filter).ate, 1e-9) << row.filter;
		}
	}
	std::printf("[ measured ] MRCLAM excerpt: default %.4f m, dynamic %.4f m\n",
	            app.rows[4].metrics.ate, e.r.at("dynamic").ate);
}

// Issue 12 on real data: the excerpt imported with --anonymous (robot3_excerpt_anon, seed 1: the
// 20 subjects permuted into IDs 0..19) through dynslam-compare's static_all and
// dynamic_classified rows, scored against robot3_excerpt_anon_gt_classes.csv, with the classify_*
// keys of config/mrclam_compare.ini (classify_static_test = map, chosen on Dataset 6 robots 1-3;
// doc/results/real-data.md 6.2). Measured 2026-11-24: static_all 0.3205 m, dynamic_classified
// 0.0997 m (0.3625 m with the robot-frame test of the library defaults), the same ATE as on the
// labelled rawlog (neither filter uses the ID values, only their identity); class precision 1,
// recall 0.788, F1 0.881, group ARI 0.775. Issue 12's target (<= static_all and within 25 % of the
// labelled dynamic's 0.109 m) is met here. Thresholds: ATE < 3 x the measured value and below
// static_all's, F1 > about half the measured value, precision > 0.5.
TEST(RealDataExcerpt, AnonymousImportThroughTheClassifyingFilter)
{
	const std::string anon =
	    std::string(DYNSLAM_BINARY_DIR) + "/datasets/mrclam/robot3_excerpt_anon.rawlog";
	apps::CCompareApp app;
	app.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const char* argv[] = {"dynslam-compare",
	                      "-c",
	                      kIni.c_str(),
	                      "-r",
	                      anon.c_str(),
	                      "--no-figures",
	                      "-q",
	                      "--filters",
	                      "static_all,dynamic_classified"};
	ASSERT_TRUE(app.initialize(int(std::size(argv)), argv));
	app.run();
	ASSERT_TRUE(app.hasGroundTruth);
	ASSERT_EQ(app.rows.size(), 2u);
	const auto& e = excerpt();
	const auto& all = app.rows[0];
	const auto& cls = app.rows[1];
	ASSERT_EQ(cls.filter, "dynamic_classified");
	// The ID values do not matter to either filter: the labelled rawlog gives the same paths.
	EXPECT_NEAR(all.metrics.ate, e.r.at("static_all").ate, 1e-9);
	EXPECT_NEAR(cls.metrics.ate, e.r.at("dynamic_classified").ate, 1e-9);
	// The landmark truth is keyed by the anonymous IDs: all 15 scored.
	EXPECT_EQ(cls.metrics.static_map.n_xy, 15u);
	EXPECT_LT(cls.metrics.ate, 0.3);
	EXPECT_LT(cls.metrics.ate, all.metrics.ate);
	ASSERT_TRUE(cls.classes.has_value());
	EXPECT_GT(cls.classes->f1, 0.45);
	EXPECT_GT(cls.classes->precision, 0.5);
	EXPECT_FALSE(all.classes.has_value());
	std::cout << "anonymous excerpt: static_all ATE " << all.metrics.ate
	          << " m, dynamic_classified " << cls.metrics.ate << " m, class P/R/F1 "
	          << cls.classes->precision << " / " << cls.classes->recall << " / " << cls.classes->f1
	          << ", ARI " << cls.classes->ari << "\n";
	// The shipped classify_static_test = map (doc/results/real-data.md 6.2) against the robot-frame
	// test on the same data: the map test must be the one that runs and it must help here.
	// Measured 2026-11-25: map ATE 0.0997 m, recall 0.788, F1 0.881; robot 0.1296 m, 0.682,
	// 0.811. A map test that always passes gives 0.2745 m, recall 0.347, F1 0.515 (the old
	// assertions above stayed green with both breaks).
	apps::CCompareApp robotApp;
	robotApp.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	ASSERT_TRUE(robotApp.initialize(int(std::size(argv)), argv));
	robotApp.params.write("Classify", "classify_static_test", "robot");
	robotApp.run();
	ASSERT_EQ(robotApp.rows.size(), 2u);
	const auto& robot = robotApp.rows[1];
	ASSERT_TRUE(robot.classes.has_value());
	std::cout << "  with classify_static_test = robot: ATE " << robot.metrics.ate
	          << " m, class P/R/F1 " << robot.classes->precision << " / " << robot.classes->recall
	          << " / " << robot.classes->f1 << "\n";
	EXPECT_GT(cls.classes->recall, 0.6);
	EXPECT_GT(cls.classes->f1, 0.7);
	EXPECT_GT(robot.metrics.ate - cls.metrics.ate, 0.01);
	EXPECT_GT(cls.classes->recall - robot.classes->recall, 0.03);
}
