/** Issue 12's simulator effects ([Effects], parked / stopping agents) and the class ground
 * truth (B_gt_classes.csv): each option changes exactly what it says. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/sim/CSimulateApp.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/temp_dir.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam;
using namespace dynslam::sim;
using mrpt::obs::CObservationBearingRange;

namespace
{
std::string cfgPath(const std::string& n) { return std::string(DYNSLAM_CONFIG_DIR) + "/" + n; }

TSimulatedRun simulate(const TScenarioOptions& o)
{
	return simulateMeasurements(buildGroundTruth(o), o, o.noise_seed);
}

const CObservationBearingRange& obsAt(const TSimulatedRun& run, size_t k)
{
	return *run.frames[k]->getObservationByClass<CObservationBearingRange>();
}

/** (step, true_id) -> (range, yaw) of the true readings of a run. */
std::map<std::pair<int, int32_t>, std::pair<float, float>> readingsByTruth(const TSimulatedRun& r)
{
	std::map<std::pair<int, int32_t>, std::pair<float, float>> m;
	for (const io::TReadingClass& c : r.classes)
	{
		if (c.cls == io::TrueClass::Clutter) continue;
		const auto& z = obsAt(r, size_t(c.step)).sensedData.at(size_t(c.index));
		EXPECT_EQ(z.landmarkID, c.id) << "step " << c.step << " index " << c.index;
		m[{c.step, c.true_id}] = {z.range, z.yaw};
	}
	return m;
}

TScenarioOptions withEffects(const std::string& key, const std::string& value)
{
	std::ostringstream ini;
	dynslam_test::highwayOptions().dumpToTextStream(ini);
	return loadScenarioFromText(dynslam_test::setIniKey(ini.str(), "Effects", key, value));
}
}  // namespace

TEST(SimEffects, OffByDefaultClassesFollowTheIds)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	EXPECT_FALSE(o.effects.any());
	std::ostringstream ini;
	o.dumpToTextStream(ini);
	EXPECT_EQ(ini.str().find("[Effects]"), std::string::npos);
	const TSimulatedRun run = simulate(o);
	size_t n = 0;
	for (size_t k = 0; k < run.frames.size(); ++k) n += obsAt(run, k).sensedData.size();
	ASSERT_EQ(run.classes.size(), n);
	EXPECT_EQ(n, 1552u);
	for (const io::TReadingClass& c : run.classes)
	{
		EXPECT_EQ(c.id, c.true_id);
		EXPECT_EQ(obsAt(run, size_t(c.step)).sensedData.at(size_t(c.index)).landmarkID, c.id);
		if (ids::isStatic(c.id))
		{
			EXPECT_EQ(c.cls, io::TrueClass::Static);
			EXPECT_EQ(c.object, -1);
			EXPECT_EQ(c.feature, c.id);
		}
		else
		{
			EXPECT_EQ(c.cls, io::TrueClass::Moving);  // the shipped agents always move
			EXPECT_EQ(c.object, ids::objectOf(c.id));
			EXPECT_EQ(c.feature, ids::featureOf(c.id));
		}
	}
}

TEST(SimEffects, MissedDetectionsDropTheirFractionAndNothingElse)
{
	const TSimulatedRun base = simulate(dynslam_test::highwayOptions());
	const auto ref = readingsByTruth(base);
	size_t N = 0, kept = 0;
	for (uint32_t seed : {1u, 2u, 3u, 4u})
	{
		TScenarioOptions o = withEffects("missed_detection_probability", "0.1");
		o.noise_seed = seed;
		TScenarioOptions ob = dynslam_test::highwayOptions();
		ob.noise_seed = seed;
		const auto refSeed = readingsByTruth(simulate(ob));
		const TSimulatedRun run = simulate(o);
		const auto got = readingsByTruth(run);
		N += refSeed.size();
		kept += got.size();
		for (const auto& [key, z] : got)  // every kept reading is the unchanged reading
		{
			ASSERT_TRUE(refSeed.count(key));
			EXPECT_EQ(refSeed.at(key), z);
		}
		for (const io::TReadingClass& c : run.classes) EXPECT_EQ(c.id, c.true_id);
	}
	EXPECT_EQ(N, 4 * ref.size());
	const double p = 0.1, dropped = double(N - kept);
	const double sigma = std::sqrt(double(N) * p * (1 - p));
	EXPECT_LE(std::abs(dropped - p * double(N)), 4 * sigma)
	    << "dropped " << dropped << " of " << N << " (expected " << p * double(N) << ")";
	EXPECT_GT(dropped, 0);
}

TEST(SimEffects, ClutterCountRangeAndIds)
{
	const TScenarioOptions o = loadScenario(cfgPath("highway_clutter.ini"));
	ASSERT_EQ(o.effects.clutter_per_step, 2);
	const TSimulatedRun run = simulate(o);
	std::map<int, int> perStep;
	std::set<int32_t> clutterIds, trueIds;
	size_t inner = 0, total = 0;
	for (const io::TReadingClass& c : run.classes)
	{
		if (c.cls != io::TrueClass::Clutter)
		{
			trueIds.insert(c.id);
			continue;
		}
		++perStep[c.step];
		EXPECT_TRUE(clutterIds.insert(c.id).second) << "clutter ID reused: " << c.id;
		EXPECT_EQ(c.true_id, -1);
		const auto& z = obsAt(run, size_t(c.step)).sensedData.at(size_t(c.index));
		EXPECT_GT(z.range, 0);
		EXPECT_LE(z.range, o.sensor_range * (1 + 1e-6));
		inner += z.range < o.sensor_range / std::sqrt(2.0);  // half the disc's area
		++total;
	}
	EXPECT_EQ(perStep.size(), o.numSteps());
	for (const auto& [k, n] : perStep) EXPECT_EQ(n, 2) << "step " << k;
	for (int32_t id : clutterIds)
	{
		EXPECT_FALSE(trueIds.count(id)) << "clutter ID " << id << " collides with a true track";
		EXPECT_TRUE(ids::isStatic(id)) << "fresh clutter IDs continue the static range";
	}
	const double sigma = std::sqrt(total * 0.25);
	EXPECT_LE(std::abs(double(inner) - 0.5 * total), 4 * sigma) << inner << " of " << total;
	// clutter_ids = unknown: MRPT's "association unknown"
	TScenarioOptions u = withEffects("clutter_per_step", "3");
	u = loadScenarioFromText(
	    [&]
	    {
		    std::ostringstream s;
		    u.dumpToTextStream(s);
		    return dynslam_test::setIniKey(s.str(), "Effects", "clutter_ids", "unknown");
	    }());
	size_t unknown = 0;
	for (const io::TReadingClass& c : simulate(u).classes)
		if (c.cls == io::TrueClass::Clutter)
		{
			EXPECT_EQ(c.id, -1);
			++unknown;
		}
	EXPECT_EQ(unknown, 3 * u.numSteps());
}

// unknown_id_probability (issue 12 item 4): that share of the true readings is written with ID
// -1, the truth keeps true_id and class; the other readings are those of the run without it.
TEST(SimEffects, UnknownIdProbabilityWritesMinusOne)
{
	const TSimulatedRun base = simulate(dynslam_test::highwayOptions());
	const TSimulatedRun all = simulate(withEffects("unknown_id_probability", "1"));
	ASSERT_EQ(all.classes.size(), base.classes.size());
	for (size_t i = 0; i < all.classes.size(); ++i)
	{
		EXPECT_EQ(all.classes[i].id, -1);
		EXPECT_EQ(all.classes[i].true_id, base.classes[i].true_id);
		EXPECT_EQ(all.classes[i].cls, base.classes[i].cls);
	}
	const TSimulatedRun some = simulate(withEffects("unknown_id_probability", "0.3"));
	ASSERT_EQ(some.classes.size(), base.classes.size());
	size_t unknown = 0;
	for (size_t i = 0; i < some.classes.size(); ++i)
	{
		if (some.classes[i].id == -1)
			++unknown;
		else
			EXPECT_EQ(some.classes[i].id, base.classes[i].id);
	}
	const double n = double(some.classes.size()), sigma = std::sqrt(n * 0.3 * 0.7);
	EXPECT_LE(std::abs(double(unknown) - 0.3 * n), 4 * sigma) << unknown << " of " << n;
	EXPECT_THROW(withEffects("unknown_id_probability", "1.5"), std::exception);
}

TEST(SimEffects, AnonymousIdsAreAPermutationThatMapsBack)
{
	const TScenarioOptions o = withEffects("anonymous_ids", "true");
	const TSimulatedRun base = simulate(dynslam_test::highwayOptions());
	const TSimulatedRun run = simulate(o);
	ASSERT_EQ(run.classes.size(), base.classes.size());
	std::map<int32_t, int32_t> fwd, bwd;
	for (const io::TReadingClass& c : run.classes)
	{
		const auto [it, isNew] = fwd.emplace(c.true_id, c.id);
		EXPECT_EQ(it->second, c.id) << "true ID " << c.true_id << " got two IDs";
		const auto [jt, isNew2] = bwd.emplace(c.id, c.true_id);
		EXPECT_EQ(jt->second, c.true_id) << "ID " << c.id << " used by two true IDs";
	}
	const io::TGroundTruth gt = buildGroundTruth(o);
	const size_t N = 80 + 4 + 4 + 2;
	size_t moved = 0;
	for (const auto& [t, a] : fwd)
	{
		EXPECT_GE(a, 0);
		EXPECT_LT(a, int32_t(N));
		moved += t != a;
	}
	EXPECT_GT(moved, N / 2) << "the permutation looks like the identity";
	// Readings sorted by ID (the order must not leak the class) and unchanged otherwise.
	for (size_t k = 0; k < run.frames.size(); ++k)
	{
		const auto& z = obsAt(run, k).sensedData;
		for (size_t i = 1; i < z.size(); ++i) EXPECT_LT(z[i - 1].landmarkID, z[i].landmarkID);
	}
	EXPECT_EQ(readingsByTruth(run), readingsByTruth(base));
	// Another run (noise seed) has another permutation.
	TScenarioOptions o2 = o;
	o2.noise_seed = 2;
	size_t same = 0;
	for (const io::TReadingClass& c : simulate(o2).classes) same += fwd.at(c.true_id) == c.id;
	EXPECT_LT(same, run.classes.size() / 2);
}

TEST(SimEffects, TrackBreaksAfterAGapGiveNewIdsOfTheSameFeature)
{
	for (bool anonymous : {false, true})
	{
		TScenarioOptions o = withEffects("track_break_gap", "4");
		o.effects.anonymous_ids = anonymous;
		const TSimulatedRun run = simulate(o);
		std::map<int32_t, std::pair<int, int32_t>> last;  // true ID -> (step, id)
		std::map<int32_t, int32_t> owner;                 // written ID -> true ID
		size_t breaks = 0;
		for (const io::TReadingClass& c : run.classes)
		{
			const auto [ot, fresh] = owner.emplace(c.id, c.true_id);
			EXPECT_EQ(ot->second, c.true_id) << "ID " << c.id << " reused by another feature";
			const auto it = last.find(c.true_id);
			if (it != last.end())
			{
				const bool gap = c.step - it->second.first - 1 >= 4;
				EXPECT_EQ(c.id != it->second.second, gap)
				    << "true ID " << c.true_id << " step " << c.step << " anonymous " << anonymous;
				breaks += gap;
				if (!anonymous && gap && ids::isObjectFeature(c.true_id))
				{
					EXPECT_TRUE(ids::isObjectFeature(c.id));
					EXPECT_EQ(ids::objectOf(c.id), c.object);
					EXPECT_NE(ids::featureOf(c.id),
					          c.feature);  // a new feature index of the object
				}
			}
			last[c.true_id] = {c.step, c.id};
		}
		EXPECT_GE(breaks, 4u) << "Agent 1 leaves the range and comes back";
	}
}

TEST(SimEffects, TrackBreakProbabilityPerReading)
{
	const TScenarioOptions o = withEffects("track_break_probability", "0.05");
	const TSimulatedRun run = simulate(o);
	std::map<int32_t, int32_t> cur;
	size_t trials = 0, breaks = 0;
	for (const io::TReadingClass& c : run.classes)
	{
		const auto it = cur.find(c.true_id);
		if (it != cur.end())
		{
			++trials;
			breaks += it->second != c.id;
		}
		cur[c.true_id] = c.id;
	}
	const double p = 0.05, sigma = std::sqrt(trials * p * (1 - p));
	EXPECT_LE(std::abs(double(breaks) - p * trials), 4 * sigma) << breaks << " of " << trials;
}

TEST(SimEffects, ParkedCarDrivesOffAndMovingCarStops)
{
	const TScenarioOptions o = loadScenario(cfgPath("highway_parked_driveoff.ini"));
	ASSERT_EQ(o.highway.agents.size(), 6u);
	const io::TGroundTruth gt = buildGroundTruth(o);
	const size_t onset = 40, stop = 68;  // t = 20 s and 34 s
	// Agent 4 (object 3): parked until 20 s, then moves.
	const auto& f3 = gt.objects[3].features;
	for (size_t k = 1; k <= onset; ++k) EXPECT_EQ((f3[k] - f3[0]).norm(), 0.0) << "step " << k;
	EXPECT_GT((f3[onset + 1] - f3[onset]).norm(), 0.05);
	// Agent 5 (object 4): never moves.
	for (size_t k = 1; k < gt.numSteps(); ++k)
		EXPECT_EQ((gt.objects[4].features[k] - gt.objects[4].features[0]).norm(), 0.0);
	// Agent 6 (object 5): moves, then rests from 34 s on with its heading kept.
	const auto& f5 = gt.objects[5].features;
	EXPECT_GT((f5[stop - 1] - f5[stop - 2]).norm(), 0.0);
	for (size_t k = stop; k < gt.numSteps(); ++k)
		EXPECT_EQ((f5[k] - f5[stop]).norm(), 0.0) << "step " << k;
	EXPECT_NEAR((f5[stop].col(0) - f5[stop].col(1)).norm(), (f5[0].col(0) - f5[0].col(1)).norm(),
	            1e-9);
	EXPECT_NEAR(f5[stop](1, 0) - f5[stop](1, 2), f5[0](1, 0) - f5[0](1, 2), 1e-9);  // no flip
	// Speeds whose ramps do not cancel exactly in floating point (13.1 -> 12.7 -> 0): the
	// body still rests exactly, heading kept (without the hold it drifts and turns by pi).
	{
		std::ostringstream ini;
		o.dumpToTextStream(ini);
		std::string t = dynslam_test::setIniKey(ini.str(), "Agent6", "speed", "13.1");
		t = dynslam_test::setIniKey(t, "Agent6", "speed_changes", "[10 3 12.7]");
		const io::TGroundTruth g2 = buildGroundTruth(loadScenarioFromText(t));
		const auto& f = g2.objects[5].features;
		for (size_t k = stop; k < g2.numSteps(); ++k)
			EXPECT_EQ((f[k] - f[stop]).norm(), 0.0) << "step " << k;
		EXPECT_NEAR(f.back()(0, 0) - f.back()(0, 2), f[0](0, 0) - f[0](0, 2), 1e-9)
		    << "the car turned round at rest";
	}
	// The true class flips at the onset and at the stop.
	const TSimulatedRun run = simulate(o);
	size_t n3s = 0, n3m = 0, n4 = 0, n5s = 0, n5m = 0;
	for (const io::TReadingClass& c : run.classes)
	{
		if (c.object == 3)
		{
			EXPECT_EQ(c.cls,
			          size_t(c.step) <= onset ? io::TrueClass::Static : io::TrueClass::Moving);
			(c.cls == io::TrueClass::Static ? n3s : n3m)++;
		}
		if (c.object == 4)
		{
			EXPECT_EQ(c.cls, io::TrueClass::Static);
			++n4;
		}
		if (c.object == 5)
		{
			EXPECT_EQ(c.cls,
			          size_t(c.step) >= stop ? io::TrueClass::Static : io::TrueClass::Moving);
			(c.cls == io::TrueClass::Static ? n5s : n5m)++;
		}
	}
	EXPECT_GT(n3s, 0u);
	EXPECT_GT(n3m, 0u);
	EXPECT_GT(n4, 0u);
	EXPECT_GT(n5s, 0u);
	EXPECT_GT(n5m, 0u);
}

TEST(SimEffects, BadOptionsNameTheKey)
{
	std::ostringstream s;
	loadScenario(cfgPath("highway_parked_driveoff.ini")).dumpToTextStream(s);
	const std::string ini = s.str();
	auto fails = [&](const std::string& text, const std::string& what)
	{
		try
		{
			loadScenarioFromText(text);
			ADD_FAILURE() << "accepted: " << what;
		}
		catch (const std::exception& e)
		{
			EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
		}
	};
	using dynslam_test::setIniKey;
	fails(setIniKey(ini, "Effects", "missed_detection_probability", "1.5"),
	      "missed_detection_probability");
	fails(setIniKey(ini, "Effects", "clutter_ids", "maybe"), "clutter_ids");
	fails(setIniKey(ini, "Effects", "track_break_probability", "2"), "track_break_probability");
	fails(setIniKey(ini, "Effects", "clutter_per_step", "-1"), "clutter_per_step");
	fails(setIniKey(ini, "Effects", "anonymus_ids", "true"), "anonymus_ids");
	fails(setIniKey(ini, "Agent4", "speed_changes", "[21 3 10]"), "speed_changes");
	fails(setIniKey(ini, "Agent4", "lane_changes", "[10 3 1]"), "lane_changes");
	fails(setIniKey(ini, "Agent6", "speed_changes", "[29 3 10]"), "stop_at_s");
	fails(setIniKey(ini, "Agent5", "speed_changes", "[10 3 10]"), "start_moving_at_s");
	// dump -> reload identical for the new configs
	for (const char* n :
	     {"highway_parked_driveoff.ini", "highway_clutter.ini", "highway_anonymous.ini"})
	{
		std::ostringstream a, b;
		loadScenario(cfgPath(n)).dumpToTextStream(a);
		loadScenarioFromText(a.str()).dumpToTextStream(b);
		EXPECT_EQ(a.str(), b.str()) << n;
	}
}

TEST(SimEffects, ClassFileRoundTripAndAppWritesIt)
{
	const TSimulatedRun run = simulate(loadScenario(cfgPath("highway_clutter.ini")));
	const dynslam_test::TTempDir tmp("test_classes");  // removed at the end of the test
	const std::filesystem::path dir = tmp.path();
	const std::string p = (dir / "x_gt_classes.csv").string();
	io::writeClassGroundTruth(run.classes, p);
	EXPECT_EQ(io::readClassGroundTruth(p), run.classes);
	// malformed rows are rejected naming file and line
	{
		std::ofstream f(p);
		f << "step,t,index,id,true_id,class,object,feature\n0,1,0,5,5,static,-1,5\n"
		  << "0,1,1,7,-1,parked,-1,-1\n";
	}
	try
	{
		io::readClassGroundTruth(p);
		ADD_FAILURE() << "accepted an unknown class";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find(p + ":3"), std::string::npos) << e.what();
	}
	CSimulateApp app;
	app.options = loadScenario(cfgPath("highway_anonymous.ini"));
	app.outDir = dir.string();
	app.run();
	const auto rows = io::readClassGroundTruth((dir / "highway_anonymous_gt_classes.csv").string());
	EXPECT_EQ(rows.size(), app.numMeasurements);
}
