/** The object-centric models end to end (issue 13): dynslam-compare on a generated scenario
 * whose cars turn (circle of radius 70 m) and brake hard (config/generated_turning_braking.ini,
 * the shipped datasets/turning_braking.rawlog): the object models must not drag the ego; and
 * dynslam-montecarlo honours prior_gauge (doc/results/results.md 4.10); the smoothing row (Alg. 6).
 */
#include <apps_test_utils.h>
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/CMonteCarloApp.h>

#include <cstdio>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::TArgs;

TEST(CompareApp, TurningBrakingObjectsDoNotDragTheEgo)
{
	CCompareApp app;
	TArgs a({"-c", apps_test::configFile("compare_turning_braking.ini"), "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 5u);
	EXPECT_EQ(app.rows[0].filter, "static_landmarks_only");
	EXPECT_EQ(app.rows[2].filter, "dynamic_cv");
	EXPECT_EQ(app.rows[3].filter, "dynamic_ctrv");
	EXPECT_EQ(app.rows[4].filter, "default");
	// This INI already sets the anchored gauge: the default profile's row is `dynamic`.
	EXPECT_EQ(app.rows[4].metrics.ate, app.rows[1].metrics.ate);
	const double so = app.rows[0].metrics.ate, dy = app.rows[1].metrics.ate;
	const double cv = app.rows[2].metrics.ate, ctrv = app.rows[3].metrics.ate;
	std::printf(
	    "[ measured ] turning/braking ATE: static_landmarks_only %.4f m, dynamic %.4f m, "
	    "dynamic_cv %.4f m, dynamic_ctrv %.4f m\n",
	    so, dy, cv, ctrv);
	// The target: no worse than 1.05 x static_landmarks_only.
	// Measured 2026-11-25 with the shipped cv_* keys (setting E, doc/results/results.md 4.10: D
	// of 4.8 without cv_ego_velocity_std and with prior_gauge = anchor, chosen on highway and
	// tunnel development seeds; this scenario is a held-out check): 0.0144, 0.0084, 0.0087, 0.0098
	// m (with D: 0.0144, 0.0085, 0.0089, 0.0096). The static baseline is MRPT's filter with
	// range-bearing noise equivalent to the Cartesian noise only at 27.5 m, hence worse than the
	// dynamic EKF, which equals the oracle that drops the moving features: against that one cv
	// costs 4 % and ctrv 17 % (D: 5 %, 14 %) (with setting B, gate 0.5: cv 0.99 x, ctrv 0.85 x;
	// with 4.3's keys, gate 0.999 and the inflation rule, cv 1.32 x and ctrv 1.27 x).
	EXPECT_LE(cv, 1.05 * so);  // the target; measured 0.61 x
	EXPECT_LE(ctrv, 1.05 * so);
	EXPECT_LE(cv, 1.25 * dy);  // the turning and braking objects do not drag the ego far
	EXPECT_LE(ctrv, 1.5 * dy);
	EXPECT_LT(ctrv, 0.05);
}

TEST(CompareApp, SmoothingFilterRowRunsAlg6)
{
	// [Compare] filters = dynamic, dynamic_smoothing on the shipped highway: the second row is
	// the same filter with the paper's smoothing (Alg. 6, K >= 3 poses, Sigma_s of
	// config/run_highway_smoothing.ini). Measured ATE: 0.127555 / 0.127578 m (README: the
	// smoothing changes the ego in the fifth digit). Equal numbers would mean it did not run.
	std::string ini = apps_test::shippedIniText("compare_highway.ini");
	const std::string from =
	    "filters             = static_all, static_landmarks_only, dynamic, "
	    "dynamic_classified, default";
	ASSERT_NE(ini.find(from), std::string::npos);
	ini.replace(ini.find(from), from.size(), "filters = dynamic, dynamic_smoothing");
	ini.replace(ini.find("[DynamicKFSLAM]\n"), 16, "[DynamicKFSLAM]\nSigma_s = [1e-2 1e-2 1e-3]\n");
	const std::string dir = apps_test::freshDir("smoothing");
	apps_test::writeFile(dir + "/compare.ini", ini);
	CCompareApp app;
	TArgs a({"-c", dir + "/compare.ini", "-r", apps_test::dataset("highway.rawlog"), "--gt",
	         apps_test::dataset("highway"), "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.rows.size(), 2u);
	EXPECT_EQ(app.rows[0].filter, "dynamic");
	EXPECT_EQ(app.rows[1].filter, "dynamic_smoothing");
	const double dy = app.rows[0].metrics.ate, sm = app.rows[1].metrics.ate;
	std::printf("[ measured ] highway ATE: dynamic %.6f m, dynamic_smoothing %.6f m\n", dy, sm);
	EXPECT_NEAR(dy, 0.1276, 0.002);  // the README's table
	EXPECT_NE(sm, dy);
	EXPECT_NEAR(sm, dy, 0.01 * dy);
}

namespace
{
/** dynslam-montecarlo on config/montecarlo.ini at w3v1 (2 runs), with `dyn` added to
 * [DynamicKFSLAM] and `mc` to [MonteCarlo]. */
void monteCarloWith(CMonteCarloApp& app, const std::string& tag, const std::string& dyn,
                    const std::string& mc)
{
	std::string ini = apps_test::shippedIniText("montecarlo.ini");
	const auto s = ini.find("scenario = highway.ini");
	ini.replace(s, 22, "scenario = " + apps_test::configFile("highway.ini"));
	// The keys set here replace the INI's (the last of two equal keys would win).
	for (const std::string& kv : {dyn, mc})
		if (!kv.empty())
		{
			const std::string key = kv.substr(0, kv.find(' '));
			for (auto p = ini.find("\n" + key + " "); p != std::string::npos;
			     p = ini.find("\n" + key + " "))
				ini.replace(p + 1, ini.find('\n', p + 1) - p, "");
		}
	ini.replace(ini.find("[DynamicKFSLAM]\n"), 16, "[DynamicKFSLAM]\n" + dyn);
	ini.replace(ini.find("[MonteCarlo]\n"), 13, "[MonteCarlo]\n" + mc);
	const std::string dir = apps_test::freshDir("mc_gauge_" + tag);
	apps_test::writeFile(dir + "/mc.ini", ini);
	TArgs a({"-c", dir + "/mc.ini", "--runs", "2", "--levels", "w3v1", "--threads", "1", "-q",
	         "--no-figures"});
	EXPECT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
}
double egoNees(const CMonteCarloApp& app)
{
	double s = 0;
	for (const auto& r : app.results)
		for (const auto& n : r.consistency.ego.samples) s += n.value;
	return s;
}
}  // namespace

TEST(MonteCarloApp, PriorGaugeAnchorIsHonoured)
{
	// prior_gauge = anchor through the app (issue 13, doc/results/results.md 4.10): with the
	// protocol's Sigma_0 = Sigma_w the anchored mean equals the prior filter's with Sigma_0 = 0
	// (the same ATE to the last digit), while its reported covariance carries N Sigma_0 N^T
	// (another ego NEES); the prior gauge with Sigma_w differs (the leak of 4.3.2).
	CMonteCarloApp anchor, zero, prior;
	monteCarloWith(anchor, "anchor", "prior_gauge = anchor\n", "");
	monteCarloWith(zero, "zero", "Sigma_0 = [0 0 0]\n", "initial_covariance = ini\n");
	ASSERT_EQ(zero.sigma0FromLevel, false);
	monteCarloWith(prior, "prior", "", "");
	ASSERT_EQ(anchor.results.size(), 2u);
	ASSERT_EQ(zero.results.size(), 2u);
	ASSERT_EQ(prior.results.size(), 2u);
	for (size_t i = 0; i < 2; ++i)
	{
		EXPECT_EQ(anchor.results[i].metrics.ate, zero.results[i].metrics.ate) << i;
		EXPECT_NE(anchor.results[i].metrics.ate, prior.results[i].metrics.ate) << i;
	}
	std::printf(
	    "[ measured ] w3v1, 2 runs: ego NEES sum anchor %.4g, Sigma_0 = 0 %.4g, prior %.4g\n",
	    egoNees(anchor), egoNees(zero), egoNees(prior));
	EXPECT_LT(egoNees(anchor), egoNees(zero));  // the output term widens the reported covariance
}
