// Per-run records of dynslam-montecarlo --shard (run_records.h): lossless round trip and clear
// errors on malformed files.
#include <dynslam/eval/run_records.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

using namespace dynslam::eval;

namespace
{
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TRunRecordFile sample()
{
	TRunRecordFile f;
	f.sweep = {{"levels", "w1v1,w3v3"}, {"runs", "2"}, {"seed", "1"}};
	TRunRecord r;
	r.level = "w3v3";
	r.run = 1;
	r.seed = 8002;
	r.steps = 121;
	r.metrics.ego = {0.1 / 3.0, std::sqrt(2.0) * 1e-7, 1e-300, 121, 121};
	r.metrics.static_map = {kNaN, kNaN, kNaN, 0, 0};
	r.metrics.ate = M_PI;
	r.metrics.ego_skipped = 3;
	r.metrics.landmarks_missing = 4;
	r.metrics.landmarks_unmatched = 5;
	r.metrics.object_estimates_unmatched = 6;
	r.metrics.ms_per_step = 0.0917;
	TObjectMetrics o;
	o.object = 2;
	o.translation_only = true;
	o.features = {0.25, 1.0 / 7.0, kNaN, 1, 0};
	o.poses = {2.0, 3.0, kNaN, 50, 0};
	o.features_missing = 1;
	o.poses_skipped = 7;
	r.metrics.objects = {o, o};
	r.metrics.objects[1].object = 0;
	r.consistency.ego.samples = {{0, 1.0 / 3.0, 3}, {5, 2.5e-17, 3}};
	r.consistency.ego.skipped_singular = 2;
	r.consistency.map.samples = {{0, 171.123456789, 160}};
	r.consistency.map_joint_cov = true;
	r.consistency.object_poses[2].samples = {{9, 0.5, 2}};
	r.consistency.object_poses[-1].samples = {};
	f.runs = {r, r};
	f.runs[1].run = 0;
	return f;
}
}  // namespace

TEST(RunRecords, RoundTripIsBitExact)
{
	const TRunRecordFile f = sample();
	std::ostringstream a;
	writeRunRecords(a, f);
	std::istringstream in(a.str());
	const TRunRecordFile g = readRunRecords(in, "mem");
	std::ostringstream b;
	writeRunRecords(b, g);
	EXPECT_EQ(a.str(), b.str());
	ASSERT_EQ(g.runs.size(), 2u);
	EXPECT_EQ(g.sweep, f.sweep);
	const auto& x = f.runs[0];
	const auto& y = g.runs[0];
	EXPECT_EQ(y.level, "w3v3");
	EXPECT_EQ(y.seed, 8002u);
	EXPECT_TRUE(sameBits(x.metrics.ego.x, y.metrics.ego.x));
	EXPECT_TRUE(sameBits(x.metrics.ego.y, y.metrics.ego.y));
	EXPECT_TRUE(sameBits(x.metrics.ego.theta, y.metrics.ego.theta));
	EXPECT_TRUE(std::isnan(y.metrics.static_map.x));
	EXPECT_TRUE(sameBits(x.metrics.ate, y.metrics.ate));
	EXPECT_EQ(y.metrics.object_estimates_unmatched, 6u);
	ASSERT_EQ(y.metrics.objects.size(), 2u);
	EXPECT_TRUE(y.metrics.objects[0].translation_only);
	EXPECT_TRUE(sameBits(y.metrics.objects[0].features.y, 1.0 / 7.0));
	EXPECT_EQ(y.metrics.objects[0].poses_skipped, 7u);
	ASSERT_EQ(y.consistency.ego.samples.size(), 2u);
	EXPECT_TRUE(sameBits(y.consistency.ego.samples[1].value, 2.5e-17));
	EXPECT_EQ(y.consistency.ego.skipped_singular, 2u);
	EXPECT_TRUE(y.consistency.map_joint_cov);
	EXPECT_EQ(y.consistency.map.samples[0].dof, 160);
	ASSERT_EQ(y.consistency.object_poses.size(), 2u);
	EXPECT_EQ(y.consistency.object_poses.at(2).samples[0].key, 9);
}

TEST(RunRecords, MalformedFilesNameTheLine)
{
	std::ostringstream a;
	writeRunRecords(a, sample());
	std::string text = a.str();
	const auto pos = text.find("scalars ");
	text.replace(pos, 8, "scalarz ");
	std::istringstream in(text);
	try
	{
		readRunRecords(in, "x.runs");
		FAIL();
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("run records 'x.runs', line 7: expected 'scalars'"),
		          std::string::npos)
		    << e.what();
	}
	std::istringstream trunc(a.str().substr(0, a.str().rfind("map_joint_cov")));
	EXPECT_THROW(readRunRecords(trunc, "t.runs"), std::runtime_error);
	std::istringstream other("something else\n");
	EXPECT_THROW(readRunRecords(other, "o.runs"), std::runtime_error);
}
