/** dynslam-montecarlo --shard i/n and --merge (issue 16, item 12): shards run disjoint parts of
 * the (level, run) grid with the seeds of the whole sweep; merging their per-run records gives
 * the single-machine tables byte for byte. A missing shard or a shard of another sweep is an
 * error. Small sweeps (2 levels x 3 runs) so the test stays short. */
#include <apps_test_utils.h>
#include <dynslam/apps/CMonteCarloApp.h>

#include <set>

using namespace dynslam::apps;
using apps_test::TArgs;

namespace
{
CMonteCarloApp runMc(const std::vector<std::string>& extra)
{
	CMonteCarloApp app;
	std::vector<std::string> a{"--runs",    "3", "--levels",     "w1v1,w3v3",
	                           "--threads", "2", "--no-figures", "-q"};
	a.insert(a.end(), extra.begin(), extra.end());
	TArgs args(a);
	EXPECT_TRUE(app.initialize(args.argc(), args.argv()));
	app.run();
	return app;
}

/** runs.csv without its last column (ms_per_step: a wall time, different in every process). */
std::vector<std::string> runsWithoutTiming(const std::string& path)
{
	std::vector<std::string> out;
	for (const auto& l : apps_test::readLines(path)) out.push_back(l.substr(0, l.rfind(',')));
	return out;
}
}  // namespace

TEST(MonteCarloShards, MergedShardsEqualTheSingleMachineTablesByteForByte)
{
	const std::string root = apps_test::freshDir("shards");
	const CMonteCarloApp single = runMc({"--out", root + "/single"});
	ASSERT_EQ(single.results.size(), 6u);
	// Three shards of six jobs: 2 runs each, from both levels.
	std::set<std::pair<std::string, int>> seen;
	for (int i = 1; i <= 3; ++i)
	{
		const std::string dir = root + "/s" + std::to_string(i);
		const CMonteCarloApp sh = runMc({"--shard", std::to_string(i) + "/3", "--out", dir});
		ASSERT_EQ(sh.results.size(), 2u);
		// The documented rule: job j = level index * runs + run goes to shard j mod n + 1.
		for (const auto& r : sh.results)
			EXPECT_EQ(((r.level == "w1v1" ? 0 : 1) * 3 + r.run) % 3, i - 1) << r.level << r.run;
		for (const auto& r : sh.results)
		{
			EXPECT_TRUE(seen.insert({r.level, r.run}).second) << "job run twice";
			EXPECT_EQ(r.seed, single.runSeed(r.level, r.run));  // the whole sweep's seeds
		}
		EXPECT_TRUE(
		    std::filesystem::is_regular_file(dir + "/shard_" + std::to_string(i) + "_of_3.runs"));
		EXPECT_FALSE(std::filesystem::exists(dir + "/table1.md"));  // a shard has no tables
	}
	EXPECT_EQ(seen.size(), 6u);

	CMonteCarloApp merged;
	TArgs a({"--merge", root + "/s1", root + "/s2", root + "/s3", "--out", root + "/merged",
	         "--no-figures", "-q"});
	ASSERT_TRUE(merged.initialize(a.argc(), a.argv()));
	merged.run();
	EXPECT_EQ(merged.mergedFiles.size(), 3u);
	for (const char* f : {"table1.md", "table1.csv", "nees_summary.csv", "nees_summary.md",
	                      "nees_ego_w1v1.csv", "nees_ego_w3v3.csv"})
	{
		const std::string x = apps_test::readFile(root + "/single/" + f);
		EXPECT_FALSE(x.empty()) << f;
		EXPECT_EQ(x, apps_test::readFile(root + "/merged/" + f)) << f;
	}
	EXPECT_EQ(runsWithoutTiming(root + "/single/runs.csv"),
	          runsWithoutTiming(root + "/merged/runs.csv"));
}

TEST(MonteCarloShards, MissingShardAndForeignShardAreErrors)
{
	const std::string root = apps_test::freshDir("bad");
	runMc({"--shard", "1/2", "--out", root + "/a"});
	auto merge = [&](const std::vector<std::string>& dirs)
	{
		CMonteCarloApp m;
		std::vector<std::string> a{"--merge"};
		a.insert(a.end(), dirs.begin(), dirs.end());
		a.push_back("-q");
		TArgs args(a);
		EXPECT_TRUE(m.initialize(args.argc(), args.argv()));
		m.run();
	};
	try
	{
		merge({root + "/a"});
		FAIL() << "merged an incomplete sweep";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("a shard missing?"), std::string::npos) << e.what();
	}
	// Shard 2 of a sweep with another seed.
	runMc({"--shard", "2/2", "--seed", "5", "--out", root + "/b"});
	try
	{
		merge({root + "/a", root + "/b"});
		FAIL() << "merged shards of different sweeps";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("another sweep"), std::string::npos) << e.what();
	}
	// Bad --shard values.
	for (const char* bad : {"0/2", "3/2", "1-2", "x/2", "1/0"})
	{
		CMonteCarloApp m;
		TArgs args({"--shard", bad, "--out", root + "/c", "-q"});
		EXPECT_THROW(m.initialize(args.argc(), args.argv()), std::invalid_argument) << bad;
	}
}
