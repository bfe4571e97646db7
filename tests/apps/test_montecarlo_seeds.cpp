/** dynslam-montecarlo's noise seeds as literals (issue 32, "Test gaps to close"): run r of level L
 * (index i of w1v1..w3v3) has the seed base + 1000 i + r (CMonteCarloApp.h). The shard test
 * compares shards against the same function, so a rule shifted in every run would pass it; here
 * the seeds are written out, and a run is reproduced by another sweep whose base seed gives the
 * same run seed. */
#include <apps_test_utils.h>
#include <dynslam/apps/CMonteCarloApp.h>

using namespace dynslam::apps;
using apps_test::TArgs;

TEST(MonteCarloSeeds, RunSeedsAreBasePlus1000LevelIndexPlusRun)
{
	CMonteCarloApp app;  // base seed 1
	EXPECT_EQ(app.runSeed("w1v1", 0), 1u);
	EXPECT_EQ(app.runSeed("w1v1", 24), 25u);
	EXPECT_EQ(app.runSeed("w1v2", 0), 1001u);
	EXPECT_EQ(app.runSeed("w2v2", 3), 4004u);
	EXPECT_EQ(app.runSeed("w3v3", 0), 8001u);
	app.seed = 100;
	EXPECT_EQ(app.runSeed("w1v3", 7), 2107u);
	EXPECT_EQ(app.runSeed("w3v1", 0), 6100u);
}

TEST(MonteCarloSeeds, ARunUsesItsSeedWhateverTheSweep)
{
	const auto run = [](const std::vector<std::string>& a)
	{
		CMonteCarloApp app;
		std::vector<std::string> args{"--threads", "2", "--no-figures", "-q"};
		args.insert(args.end(), a.begin(), a.end());
		TArgs t(args);
		EXPECT_TRUE(app.initialize(t.argc(), t.argv()));
		app.run();
		return app;
	};
	const CMonteCarloApp a = run({"--runs", "2", "--levels", "w1v2,w3v1", "--seed", "10"});
	ASSERT_EQ(a.results.size(), 4u);
	const std::vector<std::pair<std::string, uint64_t>> expected{
	    {"w1v2", 1010}, {"w1v2", 1011}, {"w3v1", 6010}, {"w3v1", 6011}};
	for (size_t i = 0; i < 4; ++i)
	{
		EXPECT_EQ(a.results[i].level, expected[i].first);
		EXPECT_EQ(a.results[i].run, int(i % 2));
		EXPECT_EQ(a.results[i].seed, expected[i].second) << i;
	}
	// Seed 11, run 0 of w1v2 is seed 1011: the same noise, the same result as run 1 above.
	const CMonteCarloApp b = run({"--runs", "1", "--levels", "w1v2", "--seed", "11"});
	ASSERT_EQ(b.results.size(), 1u);
	EXPECT_EQ(b.results[0].seed, 1011u);
	EXPECT_EQ(b.results[0].metrics.ate, a.results[1].metrics.ate);
	EXPECT_EQ(b.results[0].metrics.ego.theta, a.results[1].metrics.ego.theta);
	EXPECT_NE(a.results[0].metrics.ate, a.results[1].metrics.ate);  // other seeds, other noise
}
