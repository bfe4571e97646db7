/** The three apps end to end on the shipped highway dataset (app classes driven directly).
 *
 * Thresholds: about 1.5-2x the values measured on 2026-11-21 with the shipped
 * datasets/highway.rawlog (level w2v2, noise seed 1) and config/run_highway.ini:
 *   dynamic EKF ego RMSE x 0.0060 m, y 0.127 m, theta 2.7e-4 rad; static map x 0.0077 m,
 *   y 0.127 m; ATE 0.128 m; NIS inside its 95% bounds at 98% of the steps;
 *   static_landmarks_only ego y 0.115 m; static_all ego x 555 m (diverges).
 * Monte Carlo, 2 runs (seeds 1, 2 and 8001, 8002): ego y RMSE w1v1 0.032 m, w3v3 0.284 m. */
#include <apps_test_utils.h>
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/CMonteCarloApp.h>
#include <dynslam/apps/CRunApp.h>
#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::TArgs;

TEST(RunApp, HighwayDefaultMeetsAccuracyAndWritesEverything)
{
	const std::string out = apps_test::freshDir("run");
	CRunApp app;
	TArgs a({"-c", apps_test::configFile("run_highway.ini"), "-o", out, "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_TRUE(app.hasGroundTruth);
	ASSERT_TRUE(app.evaluation.has_value());
	const auto& m = app.evaluation->metrics;
	EXPECT_EQ(app.result.steps, 121u);
	EXPECT_LT(m.ego.x, 0.012);
	EXPECT_LT(m.ego.y, 0.20);
	EXPECT_LT(m.ego.theta, 5e-4);
	EXPECT_LT(m.static_map.x, 0.015);
	EXPECT_LT(m.static_map.y, 0.20);
	EXPECT_LT(m.ate, 0.20);
	EXPECT_EQ(m.landmarks_missing, 0u);
	ASSERT_EQ(m.objects.size(), 3u);
	for (const auto& o : m.objects)
	{
		EXPECT_EQ(o.features_missing, 0u) << "object " << o.object;
		EXPECT_LT(o.features.x, 0.01) << "object " << o.object;  // measured <= 0.004 m
		EXPECT_GT(o.poses.n_xy, 10u) << "object " << o.object;
	}
	EXPECT_GE(app.evaluation->summary.nis.fraction_inside, 0.90);
	// The scenario's noise (w2v2) was taken over.
	EXPECT_NE(app.scenarioNoiseUsed.find("w2v2"), std::string::npos) << app.scenarioNoiseUsed;

	for (const char* f :
	     {"ego.csv", "trajectory.tum", "landmarks.csv", "object_features.csv", "object_poses.csv",
	      "metrics.csv", "metrics.txt", "nees_ego.csv", "nis.csv", "effective_config.ini"})
		EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + f)) << f;
	for (const char* f :
	     {"map.png", "map_stretched.png", "ego_errors.png", "nees_ego.png", "nis.png"})
		EXPECT_TRUE(apps_test::isPng(out + "/" + f)) << f;
	mrpt::img::CImage map;  // equal axes: a 1 km road 60 m wide takes the minimum height
	ASSERT_TRUE(map.loadFromFile(out + "/map.png"));
	EXPECT_EQ(map.getHeight(), 400u);
	const auto ego = apps_test::readLines(out + "/ego.csv");
	ASSERT_EQ(ego.size(), 122u);
	EXPECT_EQ(ego[0].rfind("step,t,x,y,theta,sigma3_x,sigma3_y,sigma3_theta,gt_x,gt_y,gt_theta", 0),
	          0u);
	EXPECT_EQ(apps_test::readLines(out + "/trajectory.tum").size(), 121u);
	const std::string cfg = apps_test::readFile(out + "/effective_config.ini");
	EXPECT_NE(cfg.find("CDynamicKFSLAM2D::TOptions"), std::string::npos);
	EXPECT_NE(cfg.find("Sigma_xi"), std::string::npos);
	EXPECT_NE(cfg.find("method"), std::string::npos);  // TKF_options dumped too
}

TEST(RunApp, WithoutGroundTruthAndWithTheStaticBackend)
{
	const std::string out = apps_test::freshDir("nogt");
	CRunApp app;
	TArgs a({"-c", apps_test::configFile("run_highway.ini"), "-o", out, "--no-gt", "--backend",
	         "static_landmarks_only", "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	EXPECT_FALSE(app.hasGroundTruth);
	EXPECT_FALSE(app.evaluation.has_value());
	EXPECT_EQ(app.result.name, "static_landmarks_only");
	EXPECT_FALSE(std::filesystem::exists(out + "/metrics.csv"));
	EXPECT_FALSE(std::filesystem::exists(out + "/map.png"));
	// TUM time stamps from the rawlog (the scenario starts at 1.6e9 s).
	const auto tum = apps_test::readLines(out + "/trajectory.tum");
	ASSERT_EQ(tum.size(), 121u);
	EXPECT_EQ(tum[0].rfind("1600000000", 0), 0u) << tum[0];
}

TEST(RunApp, FrameworkBackendAlg1EqualsTheEkf)
{
	// backend = alg1 (the optimization framework's Alg. 1) must give the EKF's estimates
	// (Theorems 4.1, 4.2, A.1-A.5), here end to end through the app.
	auto runWith = [](const std::string& backend)
	{
		CRunApp app;
		TArgs a({"-c", apps_test::configFile("run_highway.ini"), "-o", apps_test::freshDir(backend),
		         "--backend", backend, "--no-figures", "-q"});
		EXPECT_TRUE(app.initialize(a.argc(), a.argv()));
		app.run();
		return app.result;
	};
	const TFilterRun ekf = runWith("ekf"), alg1 = runWith("alg1");
	EXPECT_EQ(alg1.name, "alg1");
	ASSERT_EQ(ekf.est.ego.size(), alg1.est.ego.size());
	double dmax = 0;
	for (size_t k = 0; k < ekf.est.ego.size(); ++k)
		dmax = std::max(dmax, (ekf.est.ego[k].mean - alg1.est.ego[k].mean).cwiseAbs().maxCoeff());
	std::cout << "max ego difference alg1 - ekf: " << dmax << "\n";
	EXPECT_LT(dmax, 1e-9);  // measured 1.1e-12 m: two algorithms, equal up to rounding
	ASSERT_EQ(ekf.est.landmarks.size(), alg1.est.landmarks.size());
}

TEST(CompareApp, DynamicBeatsNaiveStaticFilterAndWritesMetricsCsv)
{
	const std::string out = apps_test::freshDir("cmp");
	CCompareApp app;
	TArgs a({"--out", out, "-q"});  // no -c: the shipped default
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 5u);
	EXPECT_EQ(app.rows[0].filter, "static_all");
	EXPECT_EQ(app.rows[1].filter, "static_landmarks_only");
	EXPECT_EQ(app.rows[2].filter, "dynamic");
	EXPECT_EQ(app.rows[3].filter, "dynamic_classified");
	EXPECT_EQ(app.rows[4].filter, "default");
	const auto& sa = app.rows[0].metrics;
	const auto& so = app.rows[1].metrics;
	const auto& dy = app.rows[2].metrics;
	// The claim of the comparison: moving features ruin the static filter, not the dynamic one.
	EXPECT_LT(dy.ego.x, sa.ego.x);
	EXPECT_LT(dy.ego.y, sa.ego.y);
	EXPECT_LT(dy.ego.theta, sa.ego.theta);
	EXPECT_LT(dy.static_map.x, sa.static_map.x);
	EXPECT_LT(dy.static_map.y, sa.static_map.y);
	EXPECT_GT(sa.ate, 10.0);  // measured 564 m
	// ...and the dynamic EKF is about as good as the oracle that drops the moving features.
	EXPECT_LT(dy.ego.y, 1.5 * so.ego.y);
	EXPECT_LT(dy.ate, 0.20);
	EXPECT_LT(so.ate, 0.20);
	// The same filter with no ID oracle (issue 12): measured F1 0.991, ATE 0.1274 vs 0.1276 m.
	ASSERT_TRUE(app.rows[3].classes.has_value());
	EXPECT_GT(app.rows[3].classes->f1, 0.95);
	EXPECT_LT(app.rows[3].metrics.ate, 1.1 * dy.ate + 0.01);
	EXPECT_FALSE(app.rows[2].classes.has_value());
	// profiles/default.ini (anchored gauge): measured 0.1268 m; not `dynamic`'s 0.1276 m digits
	EXPECT_LT(app.rows[4].metrics.ate, 1.05 * dy.ate);
	EXPECT_GT(std::abs(app.rows[4].metrics.ate - dy.ate), 1e-5);

	const auto lines = apps_test::readLines(out + "/metrics.csv");
	ASSERT_EQ(lines.size(), 6u);
	const auto header = apps_test::splitCsv(lines[0]);
	const std::vector<std::string> required{
	    "filter",        "ego_rmse_x", "ego_rmse_y",  "ego_rmse_theta", "static_rmse_x",
	    "static_rmse_y", "ate",        "ate_aligned", "ms_per_step"};
	ASSERT_GE(header.size(), required.size());
	for (size_t i = 0; i < required.size(); ++i) EXPECT_EQ(header[i], required[i]);
	EXPECT_EQ(apps_test::splitCsv(lines[1])[0], "static_all");
	EXPECT_EQ(apps_test::splitCsv(lines[2])[0], "static_landmarks_only");
	EXPECT_EQ(apps_test::splitCsv(lines[3])[0], "dynamic");
	EXPECT_EQ(apps_test::splitCsv(lines[4])[0], "dynamic_classified");
	EXPECT_NE(std::find(header.begin(), header.end(), "class_f1"), header.end());
	for (const char* f : {"compare_map.png", "compare_map_start.png", "compare_ego_errors.png",
	                      "compare_ego_errors_without_static_all.png"})
		EXPECT_TRUE(apps_test::isPng(out + "/" + f)) << f;
	for (const char* f : {"static_all_ego.csv", "dynamic_object_poses.csv", "effective_config.ini"})
		EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + f)) << f;
}

TEST(CompareApp, TunnelObjectModelsCvHelpsTheEgo)
{
	// config/compare_tunnel.ini on datasets/tunnel.rawlog (config/tunnel.ini): 600 m without
	// static landmarks, two cars driving steadily beside the ego (issue 13).
	CCompareApp app;
	TArgs a({"-c", apps_test::configFile("compare_tunnel.ini"), "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 5u);
	EXPECT_EQ(app.rows[0].filter, "static_landmarks_only");
	EXPECT_EQ(app.rows[1].filter, "dynamic");
	EXPECT_EQ(app.rows[2].filter, "dynamic_cv");
	EXPECT_EQ(app.rows[3].filter, "dynamic_ctrv");
	EXPECT_EQ(app.rows[4].filter, "default");
	// default: the paper's filter + anchor, as this INI's dynamic row (0.7497 m both)
	EXPECT_EQ(app.rows[4].metrics.ate, app.rows[1].metrics.ate);
	EXPECT_FALSE(app.rows[4].velocity.has_value());
	const auto& so = app.rows[0].metrics;
	const auto& dy = app.rows[1].metrics;
	const auto& cv = app.rows[2].metrics;
	const auto& ctrv = app.rows[3].metrics;
	std::printf(
	    "[ measured ] tunnel ATE: static_landmarks_only %.4f m, dynamic %.4f m, "
	    "dynamic_cv %.4f m, dynamic_ctrv %.4f m\n",
	    so.ate, dy.ate, cv.ate, ctrv.ate);
	// The shipped cv_* keys, setting E (doc/results/results.md 4.10): process noise [1e-7 1e-7
	// 1e-9], cv_gate = 0.999, prior_gauge = anchor (every dynamic row), chosen on development seeds
	// of the highway and this tunnel. Measured 2026-11-25: 0.7475, 0.7497, 0.0807, 0.2641 m (with
	// D of 4.8: 0.7475, 0.7497, 0.0809, 0.3436). The paper's objects never update the ego:
	// dynamic is the oracle that drops them, within its update's rounding (0.3 %).
	EXPECT_NEAR(dy.ate, so.ate, 0.02 * so.ate);
	EXPECT_LT(ctrv.ate, 0.7 * dy.ate);  // measured ratio 0.35
	EXPECT_LT(cv.ate, 0.5 * so.ate);    // the target; measured ratio 0.108
	EXPECT_LT(cv.ate, 0.3);             // measured 0.0807 m
	// The gap (datasets/tunnel_scenario.ini: landmark_gaps = [200 800]) is scored for every row
	// (eval::gapMetrics, metrics.csv columns ate_gap ...): 72 steps; measured in the gap
	// 0.5659 / 0.5694 / 0.0736 / 0.2154 m, ego NEES 4.24 / 3.16 / 0.90 / 1.32 in [2.461, 3.592]
	// (cv and ctrv conservative on this truth, which starts at the prior mean:
	// doc/results/results.md 4.8, 4.10).
	for (const auto& r : app.rows)
	{
		ASSERT_TRUE(r.gap.has_value()) << r.filter;
		EXPECT_EQ(r.gap->steps, 72u) << r.filter;
		EXPECT_NEAR(r.gap->nees_lower, 2.461, 1e-3);
		EXPECT_NEAR(r.gap->nees_upper, 3.592, 1e-3);
		std::printf("[ measured ] %s: ATE in the gap %.4f m, outside %.4f m, NEES %.3f\n",
		            r.filter.c_str(), r.gap->ate, r.gap->ate_outside, r.gap->nees);
	}
	EXPECT_LT(app.rows[2].gap->ate, 0.5 * app.rows[0].gap->ate);  // the target, in the gap
	EXPECT_LT(app.rows[2].gap->nees, app.rows[2].gap->nees_upper);  // not overconfident
	// Object velocities (eval::objectVelocityErrors): only the models with a velocity state.
	// Measured 2026-11-25 with the shipped keys (cars at ~25 m/s): speed RMSE 0.0027 (cv) /
	// 0.0121 (ctrv) m/s over 240 velocities each; a sign or unit error gives metres per second.
	EXPECT_FALSE(app.rows[0].velocity.has_value());
	EXPECT_FALSE(app.rows[1].velocity.has_value());
	for (size_t i : {2u, 3u})
	{
		ASSERT_TRUE(app.rows[i].velocity.has_value()) << app.rows[i].filter;
		EXPECT_GE(app.rows[i].velocity->n, 200u) << app.rows[i].filter;
		EXPECT_LT(app.rows[i].velocity->speed_rmse, 0.3) << app.rows[i].filter;
	}
}

TEST(CompareApp, ClassifiedRowHasClassColumns)
{
	// config/compare_classified.ini: dynamic and dynamic_classified (feature_labels = classify,
	// issue 12, doc/results/classification.md) on the shipped highway; the class columns are scored
	// against datasets/highway_gt_classes.csv and empty for the other rows.
	const std::string out = apps_test::freshDir("cmp_classified");
	CCompareApp app;
	TArgs a({"-c", apps_test::configFile("compare_classified.ini"), "--filters",
	         "dynamic,dynamic_classified", "--no-figures", "-q", "--out", out});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 2u);
	EXPECT_FALSE(app.rows[0].classes);
	ASSERT_TRUE(app.rows[1].classes);
	const auto& c = *app.rows[1].classes;
	std::printf(
	    "[ measured ] classified: P %.4f R %.4f F1 %.4f ARI %.4f, ATE %.4f (dynamic %.4f)\n",
	    c.precision, c.recall, c.f1, c.ari, app.rows[1].metrics.ate, app.rows[0].metrics.ate);
	EXPECT_GE(c.f1, 0.95);
	EXPECT_LE(app.rows[1].metrics.ate, 1.1 * app.rows[0].metrics.ate + 0.01);
	const auto lines = apps_test::readLines(out + "/metrics.csv");
	ASSERT_EQ(lines.size(), 3u);
	const auto header = apps_test::splitCsv(lines[0]);
	const auto it = std::find(header.begin(), header.end(), "class_f1");
	ASSERT_NE(it, header.end());
	const size_t col = size_t(it - header.begin());
	EXPECT_EQ(header[col - 2], "class_precision");
	EXPECT_EQ(header[col + 1], "group_ari");
	EXPECT_EQ(apps_test::splitCsv(lines[1])[col], "") << "dynamic does not classify";
	EXPECT_NE(apps_test::splitCsv(lines[2])[col], "");
	// Object columns of the classifying row (doc/metrics.md "Objects of classifying rows"): the
	// router numbers its objects itself, so the agent_* cells are scored against the estimated
	// object matched by the readings (by index they compared unrelated objects:
	// agent1_pose_rmse_x 8.50 m against dynamic's 0.0047 m;
	// CompareApp.ClassifiedRowScoresItsAgents), and the printed notes say how the objects were
	// matched.
	const auto pc = std::find(header.begin(), header.end(), "agent1_pose_rmse_x");
	ASSERT_NE(pc, header.end());
	EXPECT_NE(apps_test::splitCsv(lines[1])[size_t(pc - header.begin())], "");
	EXPECT_NE(apps_test::splitCsv(lines[2])[size_t(pc - header.begin())], "");
	ASSERT_EQ(app.objectNotes.size(), 2u);  // the matching, then the identities
	// Three agents, no track break on the shipped highway: one identity each, none mixed.
	const eval::TIdentityCounts& ids = app.identities.at("dynamic_classified");
	EXPECT_EQ(ids.true_objects, 3u);
	EXPECT_EQ(ids.identities, 3u);
	EXPECT_EQ(ids.impure + ids.split, 0u);
	EXPECT_NE(app.objectNotes[1].find("3 object identities"), std::string::npos)
	    << app.objectNotes[1];
	EXPECT_NE(app.objectNotes[0].find("3 estimated objects matched to 3 true objects"),
	          std::string::npos)
	    << app.objectNotes[0];
}

TEST(CompareApp, ClassifiedRowScoresItsAgents)
{
	// The main job (config/compare_highway.ini): every agent cell of dynamic_classified is
	// finite and near the labelled dynamic row's (doc/metrics.md "Objects of classifying rows").
	// Measured 2026-11-25: pose x/y agent 1 0.0040/0.1043 m (dynamic 0.0047/0.1036), agent 2
	// 0.0040/0.1179 (0.0039/0.1172), agent 3 0.0038/0.0050 (0.0027/0.0029); features <= 0.0051
	// m for the cars, 0.066/0.182 m for the pedestrian (its second feature joined late through
	// a translation-only pose; dynamic 0.0028/0.1115). By number they were 8.50 and 9.75 m.
	CCompareApp app;
	TArgs a({"-c", apps_test::configFile("compare_highway.ini"), "--filters",
	         "dynamic,dynamic_classified", "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 2u);
	const auto &dyn = app.rows[0].metrics.objects, &cls = app.rows[1].metrics.objects;
	ASSERT_EQ(cls.size(), 3u);
	for (size_t k = 0; k < 3; ++k)
	{
		std::printf(
		    "[ measured ] agent %zu: pose %.5f %.5f %.5f feat %.5f %.5f (dynamic %.5f "
		    "%.5f)\n",
		    k + 1, cls[k].poses.x, cls[k].poses.y, cls[k].poses.theta, cls[k].features.x,
		    cls[k].features.y, dyn[k].poses.x, dyn[k].poses.y);
		EXPECT_EQ(cls[k].object, dyn[k].object);
		EXPECT_LT(cls[k].poses.x, 3 * dyn[k].poses.x + 0.01) << k;
		EXPECT_LT(cls[k].poses.y, 3 * dyn[k].poses.y + 0.01) << k;
		EXPECT_LT(cls[k].features.x, 0.2) << k;
		EXPECT_LT(cls[k].features.y, 0.6) << k;
		EXPECT_GT(cls[k].poses.n_xy, 10u) << k;
	}
	EXPECT_LT(cls[0].poses.theta, 0.01);
	EXPECT_LT(cls[1].poses.theta, 0.01);
	ASSERT_EQ(app.objectNotes.size(), 2u);
	EXPECT_NE(app.objectNotes[0].find("agent 1 <- object 0 (time 0 step 1"), std::string::npos)
	    << app.objectNotes[0];
}

TEST(CompareApp, ClassifiedRowWithoutClassTruthHasEmptyObjectColumns)
{
	// The highway's ground truth copied without highway_gt_classes.csv: the class_* and object
	// cells of the classifying row are empty (never matched by index), and the notes say so.
	const std::string dir = apps_test::freshDir("cmp_no_class_truth");
	for (const auto& e : std::filesystem::directory_iterator(apps_test::dataset("")))
	{
		const std::string n = e.path().filename().string();
		if (n.rfind("highway_gt_", 0) == 0 && n != "highway_gt_classes.csv")
			std::filesystem::copy_file(e.path(), dir + "/" + n);
	}
	CCompareApp app;
	TArgs a({"-c", apps_test::configFile("compare_classified.ini"), "--filters",
	         "dynamic_classified", "--gt", dir + "/highway", "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 1u);
	EXPECT_FALSE(app.rows[0].classes);
	EXPECT_FALSE(app.rows[0].velocity);
	ASSERT_FALSE(app.rows[0].metrics.objects.empty());
	for (const auto& o : app.rows[0].metrics.objects)
	{
		EXPECT_TRUE(std::isnan(o.poses.x));
		EXPECT_TRUE(std::isnan(o.features.x));
	}
	EXPECT_NE(app.tableText.find("no class ground truth"), std::string::npos) << app.tableText;
}

// Issue 12 figures (doc/results/classification.md "Figures"): with --out and figures on, a
// classifying row writes its class map and decision timeline; the timeline holds many readings
// decided moving (red) and static (blue): measured on the shipped highway 98 tracks.
TEST(CompareApp, ClassifiedRowWritesClassFigures)
{
	const std::string out = apps_test::freshDir("cmp_class_figures");
	CCompareApp app;
	TArgs a({"-c", apps_test::configFile("compare_classified.ini"), "--filters",
	         "dynamic_classified", "-q", "--out", out});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	mrpt::img::CImage map, tl;
	ASSERT_TRUE(map.loadFromFile(out + "/dynamic_classified_class_map.png"));
	ASSERT_TRUE(tl.loadFromFile(out + "/dynamic_classified_class_timeline.png"));
	// The scores and both figures share one reading of highway_gt_classes.csv.
	EXPECT_EQ(app.classTruthFilesRead, 1u);
	EXPECT_EQ(map.getWidth(), 1600u);
	EXPECT_EQ(map.getHeight(), 700u);
	EXPECT_EQ(tl.getWidth(), 1310u);
	size_t red = 0, blue = 0;
	for (unsigned y = 0; y < tl.getHeight(); ++y)
		for (unsigned x = 0; x < tl.getWidth(); ++x)
		{
			const int c0 = tl.at<uint8_t>(x, y, 0), c1 = tl.at<uint8_t>(x, y, 1),
			          c2 = tl.at<uint8_t>(x, y, 2);
			const bool ends = (c0 == 220 && c2 == 30) || (c0 == 30 && c2 == 220);
			red += ends && c1 == 30;
			blue += ends && c1 == 80;
		}
	std::printf("[ measured ] timeline: %zu red, %zu blue pixels\n", red, blue);
	EXPECT_GT(red, 1000u);
	EXPECT_GT(blue, 1000u);
}

TEST(CompareApp, ExecutableWithoutArgumentsRunsTheShippedDefault)
{
	// From a folder with no datasets/ or config/: found via the executable's share folder or the
	// source tree, and named in the output.
	const std::string cwd = apps_test::freshDir("cwd");
	const auto r = apps_test::runCommand(std::string("'") + DYNSLAM_COMPARE_EXE + "'", cwd);
	ASSERT_TRUE(r.exitedNormally) << r.output;
	EXPECT_EQ(r.exitCode, 0) << r.output;
	EXPECT_NE(r.output.find("config/compare_highway.ini"), std::string::npos) << r.output;
	EXPECT_NE(r.output.find("datasets/highway.rawlog (121 steps)"), std::string::npos) << r.output;
	for (const char* f : {"\nstatic_all ", "\nstatic_landmarks_only ", "\ndynamic "})
		EXPECT_NE(r.output.find(f), std::string::npos) << f << "\n" << r.output;
	EXPECT_FALSE(std::filesystem::exists(cwd + "/metrics.csv"));  // nothing written without --out
}

namespace
{
void runMonteCarlo(CMonteCarloApp& app, const std::vector<std::string>& args)
{
	TArgs a(args);
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
}
void expectSameMetrics(const eval::TRunMetrics& a, const eval::TRunMetrics& b,
                       const std::string& what)
{
	EXPECT_EQ(a.ego.x, b.ego.x) << what;
	EXPECT_EQ(a.ego.y, b.ego.y) << what;
	EXPECT_EQ(a.ego.theta, b.ego.theta) << what;
	EXPECT_EQ(a.static_map.x, b.static_map.x) << what;
	EXPECT_EQ(a.static_map.y, b.static_map.y) << what;
	ASSERT_EQ(a.objects.size(), b.objects.size()) << what;
	for (size_t i = 0; i < a.objects.size(); ++i)
	{
		EXPECT_EQ(a.objects[i].poses.x, b.objects[i].poses.x) << what;
		EXPECT_EQ(a.objects[i].features.y, b.objects[i].features.y) << what;
	}
}
}  // namespace

TEST(MonteCarloApp, TwoLevelsTwoRunsTableAndThreadIndependence)
{
	const std::string out = apps_test::freshDir("mc");
	CMonteCarloApp one, two, single;
	runMonteCarlo(one, {"--runs", "2", "--levels", "w1v1,w3v3", "--threads", "1", "--out", out,
	                    "-q", "--no-figures"});
	runMonteCarlo(two, {"--runs", "2", "--levels", "w1v1,w3v3", "--threads", "2", "-q"});
	EXPECT_EQ(one.threadsUsed, 1);
	EXPECT_EQ(two.threadsUsed, 2);
	ASSERT_EQ(one.results.size(), 4u);
	ASSERT_EQ(two.results.size(), 4u);
	for (size_t i = 0; i < 4; ++i)
	{
		EXPECT_EQ(one.results[i].seed, two.results[i].seed);
		expectSameMetrics(one.results[i].metrics, two.results[i].metrics,
		                  "run " + std::to_string(i));
	}
	// A run does not depend on which levels are selected either.
	runMonteCarlo(single, {"--runs", "1", "--levels", "w3v3", "--threads", "2", "-q"});
	ASSERT_EQ(single.results.size(), 1u);
	EXPECT_EQ(single.results[0].seed, one.results[2].seed);
	expectSameMetrics(single.results[0].metrics, one.results[2].metrics, "w3v3 run 0 alone");

	// Accuracy per level and graceful degradation (Table I, ego y; thresholds ~2x measured).
	ASSERT_EQ(one.table.levels.size(), 2u);
	const double w1 = one.table.levels[0].cells[1][0].mean;  // y, ego poses
	const double w3 = one.table.levels[1].cells[1][0].mean;
	EXPECT_LT(w1, 0.06);
	EXPECT_LT(w3, 0.60);
	EXPECT_GT(w3, w1);
	EXPECT_GT(one.table.levels[1].cells[0][1].mean,
	          one.table.levels[0].cells[0][1].mean);  // static x
	EXPECT_EQ(one.table.levels[0].runs, 2);

	// table1.csv: header + one row per level and quantity, ours and the paper's.
	const auto lines = apps_test::readLines(out + "/table1.csv");
	ASSERT_EQ(lines.size(), 7u);
	const auto h = apps_test::splitCsv(lines[0]);
	EXPECT_EQ(h[0], "noise_level");
	EXPECT_EQ(h[1], "quantity");
	EXPECT_NE(std::find(h.begin(), h.end(), "ego_poses_ours"), h.end());
	const auto paperCol = std::find(h.begin(), h.end(), "ego_poses_paper") - h.begin();
	ASSERT_LT(size_t(paperCol), h.size());
	const char* want[6][2] = {{"w1v1", "x_m"}, {"w1v1", "y_m"}, {"w1v1", "theta_rad"},
	                          {"w3v3", "x_m"}, {"w3v3", "y_m"}, {"w3v3", "theta_rad"}};
	for (size_t r = 0; r < 6; ++r)
	{
		const auto c = apps_test::splitCsv(lines[r + 1]);
		EXPECT_EQ(c[0], want[r][0]);
		EXPECT_EQ(c[1], want[r][1]);
	}
	EXPECT_DOUBLE_EQ(std::stod(apps_test::splitCsv(lines[1])[size_t(paperCol)]),
	                 0.008);  // paper w1v1 x
	for (const char* f :
	     {"table1.md", "nees_summary.csv", "nees_summary.md", "runs.csv", "effective_config.ini"})
		EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + f)) << f;
	EXPECT_EQ(apps_test::readLines(out + "/runs.csv").size(), 5u);
}
