/** CClassifyingRouter's groups after they are formed (doc/results/classification.md, "Grouping"):
 * a track ID reused by another point after a break restarts as a new track (counted), a
 * track decided moving joins an object of an earlier step, a feature that stops moving with
 * its object is split off. Synthetic tracks (router_synth.h). */
#include <gtest/gtest.h>

#include <functional>
#include <set>

#include "router_synth.h"

using namespace dynslam;
using namespace dynslam::estimator;
using router_test::TSynth;

namespace
{
/** Runs `steps` steps; world(k) gives the (track ID, world point) pairs seen at step k. */
struct TRun : router_test::TRouterRun
{
	explicit TRun(const TClassifyParams& p) : TRouterRun(p, 17) {}
	void run(int steps,
	         const std::function<std::vector<std::pair<int32_t, Eigen::Vector2d>>(int)>& world)
	{
		runReadings(steps,
		            [&](int k)
		            {
			            std::vector<TReading> rd;
			            for (const auto& [id, p] : world(k)) rd.push_back({id, s.see(p)});
			            return rd;
		            });
	}
};

Eigen::Vector2d carA(int k, int f)
{
	const Eigen::Vector2d base[] = {{10, 3}, {12.5, 3}, {11, 4.5}, {13, 4.6}};
	return base[f] + Eigen::Vector2d(0.8, 0) * (k + 1);
}
Eigen::Vector2d carB(int k, int f)
{
	const Eigen::Vector2d base[] = {{10, -4}, {12.5, -4}, {11.5, -2.8}};
	return base[f] + Eigen::Vector2d(1.5, 0.1) * (k + 1);
}
}  // namespace

TEST(ClassifyGroups, IdReusedByAnotherPointAfterABreakRestartsTheTrack)
{
	// Tracks 0, 1, 2 on car A, 10 and 11 on car B, 5 and 6 static. Steps 8-13: 2, 5 and 6
	// unseen. From step 14 on ID 2 is a point of car B and ID 5 another landmark 3 m away;
	// ID 6 is its old landmark again.
	const auto world = [](int k)
	{
		std::vector<std::pair<int32_t, Eigen::Vector2d>> w{
		    {0, carA(k, 0)}, {1, carA(k, 1)}, {10, carB(k, 0)}, {11, carB(k, 1)}};
		if (k < 8 || k >= 14)
		{
			w.push_back({2, k < 8 ? carA(k, 2) : carB(k, 2)});
			w.push_back({5, k < 8 ? Eigen::Vector2d(20, 8) : Eigen::Vector2d(20, 11)});
			w.push_back({6, {24, -7}});
		}
		return w;
	};
	TClassifyParams p;
	p.reuse_gap = 5;  // default 0: off
	TRun run(p);
	run.run(24, world);
	const TRoutedStep& back = run.out[14];
	EXPECT_EQ(back.restarted, 2u) << "ID 2 (moving) and ID 5 (static) reused";
	const TRoutedReading &two = run.at(14, 4), &five = run.at(14, 5), &six = run.at(14, 6);
	EXPECT_GE(two.reading.id, kFirstResolvedId);
	EXPECT_GE(five.reading.id, kFirstResolvedId);
	EXPECT_NE(two.reading.id, five.reading.id);
	EXPECT_TRUE(two.candidate && five.candidate) << "new candidates";
	EXPECT_EQ(five.route, Route::StaticNew) << "a candidate landmark of its own";
	EXPECT_EQ(six.reading.id, 6);
	EXPECT_EQ(six.route, Route::StaticKnown) << "consistent after the same break: no restart";
	// The old landmark 5 stays in the map; the old track 2 left car A's object.
	EXPECT_EQ(run.r.tracks().at(5).cls, TrackClass::Static);
	EXPECT_EQ(run.r.tracks().at(5).last_seen, 7);
	EXPECT_EQ(run.r.tracks().count(2), 0u);
	// Later readings keep the new IDs: ID 2's new track is moving and joined car B's object,
	// ID 5's new track is a static landmark.
	const int32_t newTwo = two.reading.id, newFive = five.reading.id;
	EXPECT_EQ(run.at(23, 4).reading.id, newTwo);
	EXPECT_EQ(run.at(23, 5).reading.id, newFive);
	EXPECT_EQ(run.at(23, 5).route, Route::StaticKnown);
	ASSERT_EQ(run.r.tracks().at(newTwo).cls, TrackClass::Moving);
	EXPECT_EQ(run.r.tracks().at(newTwo).object, run.r.tracks().at(10).object);
	EXPECT_EQ(run.total(&TRoutedStep::joined), 1u);
	EXPECT_EQ(run.total(&TRoutedStep::restarted), 2u) << "no other restart";
	EXPECT_EQ(run.total(&TRoutedStep::split), 0u);

	// Off (reuse_gap = 0, and no splits): ID 2's readings feed car A's object, landmark 5 is
	// held back and then reclassified (converted) as if it had moved.
	p.reuse_gap = 0;
	p.split_count = 0;
	TRun off(p);
	off.run(24, world);
	EXPECT_EQ(off.total(&TRoutedStep::restarted), 0u);
	EXPECT_EQ(off.at(14, 4).reading.id, 2);
	EXPECT_EQ(off.at(14, 4).object, off.r.tracks().at(0).object);
	EXPECT_EQ(off.at(14, 5).route, Route::Skip);
	EXPECT_GE(off.total(&TRoutedStep::held), 2u);
}

TEST(ClassifyGroups, TrackDecidedLaterJoinsItsObject)
{
	// Car A: tracks 0 and 1 from step 0, track 3 (the same car) from step 6.
	const auto world = [](int k)
	{
		std::vector<std::pair<int32_t, Eigen::Vector2d>> w{{0, carA(k, 0)}, {1, carA(k, 1)}};
		if (k >= 6) w.push_back({3, carA(k, 3)});
		return w;
	};
	for (const bool join : {true, false})
	{
		TClassifyParams p;
		p.join = join;
		TRun run(p);
		run.run(14, world);
		const auto& t = run.r.tracks();
		ASSERT_EQ(t.at(3).cls, TrackClass::Moving);
		const int32_t a = t.at(0).object;
		const TObjectEntry& e = run.r.registry().at(a);
		EXPECT_EQ(e.founders, 2);
		EXPECT_EQ(e.poseDim(), 3);
		if (!join)
		{
			EXPECT_NE(t.at(3).object, a) << "join off: an object of its own";
			EXPECT_EQ(run.total(&TRoutedStep::joined), 0u);
			continue;
		}
		EXPECT_EQ(t.at(3).object, a);
		EXPECT_EQ(run.total(&TRoutedStep::joined), 1u);
		EXPECT_EQ(e.feature_ids, (std::vector<int32_t>{0, 1, 3}));
		EXPECT_EQ(run.r.featureId(a, t.at(3).feature), 3);
		// From its decision on, its readings are time-t readings of car A.
		const int decided = t.at(3).decided_step;
		for (int k = decided; k < 14; ++k)
		{
			EXPECT_EQ(run.at(k, 2).route, Route::ObjectTimeT) << "step " << k;
			EXPECT_EQ(run.at(k, 2).object, a);
		}
	}
}

TEST(ClassifyGroups, FeatureThatLeavesItsObjectIsSplitOff)
{
	// Tracks 0, 1, 2 move as one car; from step 10 on track 2 drifts sideways 0.6 m per step.
	const auto world = [](int k)
	{
		const Eigen::Vector2d drift(0, k >= 10 ? 0.6 * (k - 9) : 0.0);
		return std::vector<std::pair<int32_t, Eigen::Vector2d>>{
		    {0, carA(k, 0)}, {1, carA(k, 1)}, {2, carA(k, 2) + drift}};
	};
	for (const int count : {3, 0})
	{
		TClassifyParams p;
		p.split_count = count;
		TRun run(p);
		run.run(20, world);
		const int32_t a = run.r.tracks().at(0).object;
		EXPECT_EQ(run.r.tracks().at(1).object, a);
		if (count == 0)
		{
			EXPECT_EQ(run.total(&TRoutedStep::split), 0u);
			EXPECT_EQ(run.r.tracks().at(2).object, a) << "split off: stays in its object";
			continue;
		}
		EXPECT_EQ(run.total(&TRoutedStep::split), 1u);
		EXPECT_EQ(run.total(&TRoutedStep::restarted), 0u);
		// Its first count - 1 inconsistent readings held back, the next one restarts it.
		EXPECT_EQ(run.out[10].held, 1u);
		EXPECT_EQ(run.out[11].held, 1u);
		EXPECT_EQ(run.out[12].split, 1u);
		const int32_t fresh = run.at(12, 2).reading.id;
		EXPECT_GE(fresh, kFirstResolvedId);
		EXPECT_TRUE(run.at(12, 2).candidate);
		EXPECT_EQ(run.r.tracks().count(2), 0u);
		ASSERT_EQ(run.r.tracks().at(fresh).cls, TrackClass::Moving);
		EXPECT_NE(run.r.tracks().at(fresh).object, a) << "not back into the object it left";
	}
}

TEST(ClassifyGroups, BadKeysAreClearErrors)
{
	TClassifyParams p;
	p.reuse_gap = -1;
	EXPECT_THROW(CClassifyingRouter{p}, std::invalid_argument);
	p.reuse_gap = 5;
	p.split_count = -2;
	try
	{
		CClassifyingRouter r(p);
		ADD_FAILURE() << "split_count = -2 accepted";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("classify_split_count"), std::string::npos);
	}
}
