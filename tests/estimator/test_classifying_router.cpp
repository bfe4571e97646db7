/** CClassifyingRouter (feature_labels = classify, doc/results/classification.md) on synthetic
 * tracks: the SPRT decides a static and a moving point right within a bounded number of sightings,
 * its false-alarm rate over many seeded static tracks stays near the INI alpha, rigid grouping, the
 * reclassification of a static track that starts moving, and bad input. */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/classifying_router.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "router_synth.h"

using namespace dynslam;
using namespace dynslam::estimator;
using router_test::kNone;
using router_test::TSynth;

namespace
{
/** The step at which track 0 is decided (-1: never within maxSteps) and its class. */
std::pair<int, TrackClass> decide(CClassifyingRouter& r, TSynth& s, Eigen::Vector2d p,
                                  const Eigen::Vector2d& v, int maxSteps)
{
	for (int k = 0; k < maxSteps; ++k)
	{
		r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
		p += v;
		r.route(k, {{0, s.see(p)}}, kNone);
		const TTrack& t = r.tracks().at(0);
		if (t.cls != TrackClass::Candidate) return {k, t.cls};
	}
	return {-1, TrackClass::Candidate};
}
}  // namespace

TEST(ClassifyingRouter, StaticAndMovingPointsAreDecidedRightWithinFewSightings)
{
	for (unsigned seed = 1; seed <= 20; ++seed)
	{
		TSynth s(seed);
		CClassifyingRouter r;
		const auto st = decide(r, s, {15, 5}, {0, 0}, 20);
		EXPECT_EQ(st.second, TrackClass::Static) << "seed " << seed;
		EXPECT_GE(st.first, 1);
		EXPECT_LE(st.first, 3) << "seed " << seed;  // measured: 1 (the second sighting)

		TSynth m(seed + 100);
		CClassifyingRouter r2;
		const auto mv = decide(r2, m, {15, 5}, {0.4, 0.2}, 20);  // 0.45 m per step
		EXPECT_EQ(mv.second, TrackClass::Moving) << "seed " << seed;
		EXPECT_LE(mv.first, 3) << "seed " << seed;  // measured: 1
	}
}

TEST(ClassifyingRouter, FalseAlarmRateOfStaticTracksIsNearAlpha)
{
	// Weak evidence per sighting (motion_std close to the noise) so that the test runs long
	// enough for Wald's bound alpha / (1 - beta) to be the relevant one.
	TClassifyParams p;
	p.alpha = 0.05;
	p.beta = 0.05;
	p.motion_std = 0.03;
	p.max_window = 100000;
	p.forget_steps = 100000;
	const int tracks = 2000;
	TSynth s(7);
	std::vector<Eigen::Vector2d> world(tracks);
	for (auto& w : world) w = Eigen::Vector2d(5 + 20 * std::abs(s.n(1)), 20 * s.n(1));
	CClassifyingRouter r(p);
	for (int k = 0; k < 300; ++k)
	{
		r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
		std::vector<TReading> rd;
		for (int i = 0; i < tracks; ++i)
			if (r.tracks().count(i) == 0 || r.tracks().at(i).cls == TrackClass::Candidate)
				rd.push_back({i, s.see(world[size_t(i)])});
		if (rd.empty()) break;
		r.route(k, rd, kNone);
	}
	size_t moving = 0, undecided = 0;
	for (const auto& [id, t] : r.tracks())
	{
		moving += t.cls == TrackClass::Moving;
		undecided += t.cls == TrackClass::Candidate;
	}
	const double rate = double(moving) / tracks;
	const double bound = p.alpha / (1 - p.beta);
	const double sd = std::sqrt(bound * (1 - bound) / tracks);
	EXPECT_EQ(undecided, 0u);
	EXPECT_LE(rate, bound + 3 * sd) << "false alarms " << moving;
	EXPECT_GE(rate, 0.2 * p.alpha) << "false alarms " << moving;
	RecordProperty("false_alarms", int(moving));
}

TEST(ClassifyingRouter, RigidMovingTracksFormOneObjectOthersTheirOwn)
{
	TSynth s(3);
	CClassifyingRouter r;
	// Tracks 0 and 1: one car (2 m apart, same velocity); track 2: another car, other speed.
	const Eigen::Vector2d v1(0.8, 0), v2(1.6, 0.1);
	Eigen::Vector2d a(10, 3), b(12, 3), c(10, -3);
	std::vector<TRoutedStep> steps;
	for (int k = 0; k < 4; ++k)
	{
		r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
		a += v1;
		b += v1;
		c += v2;
		steps.push_back(r.route(k, {{0, s.see(a)}, {1, s.see(b)}, {2, s.see(c)}}, kNone));
	}
	const auto& t = r.tracks();
	ASSERT_EQ(t.at(0).cls, TrackClass::Moving);
	ASSERT_EQ(t.at(1).cls, TrackClass::Moving);
	ASSERT_EQ(t.at(2).cls, TrackClass::Moving);
	EXPECT_EQ(t.at(0).object, t.at(1).object);
	EXPECT_NE(t.at(0).object, t.at(2).object);
	EXPECT_EQ(r.registry().at(t.at(0).object).feature_ids.size(), 2u);
	EXPECT_EQ(r.featureId(t.at(1).object, t.at(1).feature), 1);
	// First sighting (candidate, skipped), then every reading is an object reading.
	EXPECT_EQ(steps[0].candidates, 3u);
	EXPECT_EQ(steps[1].with(Route::ObjectFirstSighting).size(), 3u);
	EXPECT_EQ(steps[2].with(Route::ObjectTimeT).size(), 3u);
}

TEST(ClassifyingRouter, StaticTrackThatStartsMovingIsReclassified)
{
	for (const bool surgery : {true, false})
	{
		TSynth s(5);
		TClassifyParams p;
		p.surgery = surgery;
		CClassifyingRouter r(p);
		Eigen::Vector2d f(12, 4);
		const int onset = 20;
		int reclassifiedAt = -1;
		size_t held = 0;
		for (int k = 0; k < 40 && reclassifiedAt < 0; ++k)
		{
			r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
			if (k >= onset) f += Eigen::Vector2d(0.05 * (k - onset + 1), 0);  // accelerates
			const bool known = k > 1;
			const TRoutedStep out = r.route(k, {{0, s.see(f)}}, [&](int32_t) { return known; });
			held += out.held;
			if (k < onset)
			{
				EXPECT_NE(r.tracks().at(0).cls, TrackClass::Moving) << "step " << k;
			}
			if (out.reclassified.empty() && out.converted.empty()) continue;
			reclassifiedAt = k;
			ASSERT_EQ(out.readings.size(), 1u);
			const int32_t obj = r.tracks().at(0).object;
			if (surgery)
			{
				// The landmark becomes f_0 of a new object whose time 0 is its last consistent
				// reading: this step's reading is a time-t sighting.
				EXPECT_TRUE(out.reclassified.empty());
				ASSERT_EQ(out.converted.size(), 1u);
				EXPECT_EQ(out.converted[0].id, 0);
				EXPECT_EQ(out.converted[0].object, obj);
				EXPECT_EQ(out.converted[0].feature, 0);
				EXPECT_EQ(out.readings[0].route, Route::ObjectTimeT);
				EXPECT_EQ(r.registry().at(obj).first_step, k - p.reclassify_count);
				EXPECT_EQ(r.registry().at(obj).feature_ids, std::vector<int32_t>{0});
			}
			else
			{
				EXPECT_TRUE(out.converted.empty());
				EXPECT_EQ(out.reclassified, std::vector<int32_t>{0});
				EXPECT_EQ(out.readings[0].route, Route::ObjectFirstSighting);
				EXPECT_EQ(r.registry().at(obj).first_step, k);
			}
		}
		ASSERT_GE(reclassifiedAt, onset);
		// reclassify_count = 3 consecutive inconsistent readings, the first ones held back.
		EXPECT_LE(reclassifiedAt - onset, 6);
		EXPECT_EQ(held, size_t(p.reclassify_count - 1));
		RecordProperty(surgery ? "delay_surgery" : "delay_restart", reclassifiedAt - onset);
	}
}

TEST(ClassifyingRouter, MovingTrackWhoseObjectStopsBecomesStatic)
{
	// A point moving 0.5 m per step that rests from step 9 on: with stop_count = 3 it becomes
	// static at its 3rd reading consistent with a static point, and that reading starts a
	// landmark; with stop_count = 0 (default) it stays moving.
	for (const int count : {0, 3})
	{
		TSynth s(21);
		TClassifyParams p;
		p.stop_count = count;
		CClassifyingRouter r(p);
		Eigen::Vector2d f(10, 3);
		int stoppedAt = -1;
		for (int k = 0; k < 25; ++k)
		{
			r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
			if (k < 10) f += Eigen::Vector2d(0.5, 0);
			const TRoutedStep out = r.route(k, {{0, s.see(f)}}, kNone);
			if (out.stopped == 0) continue;
			EXPECT_LT(stoppedAt, 0) << "stopped twice";
			stoppedAt = k;
			ASSERT_EQ(out.readings.size(), 1u);
			EXPECT_EQ(out.readings[0].route, Route::StaticNew);
		}
		if (count == 0)
		{
			EXPECT_EQ(stoppedAt, -1);
			EXPECT_EQ(r.tracks().at(0).cls, TrackClass::Moving);
			continue;
		}
		// Its last move is into the reading of step 9 (which restarts the static filter: it is
		// inconsistent with step 8's); the readings of steps 10, 11, 12 are consistent with it.
		EXPECT_EQ(stoppedAt, 9 + count);
		EXPECT_EQ(r.tracks().at(0).cls, TrackClass::Static);
		EXPECT_EQ(r.tracks().at(0).object, -1);
	}
}

TEST(ClassifyingRouter, UndecidedTracksNeverUpdateTheFilter)
{
	// Weak evidence (motion_std at the noise level): the track stays a candidate for several
	// sightings. Its first reading is a candidate landmark (StaticNew), the later ones are
	// skipped, never StaticKnown (which would update the ego), whatever the filter knows.
	TClassifyParams p;
	p.motion_std = 0.01;
	p.max_window = 50;
	TSynth s(11);
	CClassifyingRouter r(p);
	const Eigen::Vector2d f(8, 2);
	int undecidedSightings = 0;
	for (int k = 0; k < 50; ++k)
	{
		r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
		const TRoutedStep out = r.route(k, {{0, s.see(f)}}, [](int32_t) { return true; });
		if (r.tracks().at(0).cls != TrackClass::Candidate) break;
		ASSERT_EQ(out.readings.size(), 1u);
		EXPECT_TRUE(out.readings[0].candidate);
		EXPECT_EQ(out.readings[0].route, Route::Skip) << "step " << k;
		++undecidedSightings;
	}
	EXPECT_GE(undecidedSightings, 3) << "the test needs a track that stays undecided";
	TSynth s2(11);
	CClassifyingRouter r2(p);
	r2.setContext(s2.ctx(Eigen::Vector3d::Zero()));
	const TRoutedStep first = r2.route(0, {{0, s2.see(f)}}, kNone);
	EXPECT_EQ(first.readings[0].route, Route::StaticNew) << "a candidate landmark";
}

TEST(ClassifyingRouter, BadInputIsAClearError)
{
	TClassifyParams p;
	p.alpha = 1.5;
	EXPECT_THROW(CClassifyingRouter{p}, std::invalid_argument);
	p.alpha = 0.01;
	p.beta = 0;
	try
	{
		CClassifyingRouter r(p);
		ADD_FAILURE() << "beta = 0 accepted";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("classify_beta"), std::string::npos) << e.what();
	}
	EXPECT_THROW(makeRouter("bogus"), std::invalid_argument);
	EXPECT_EQ(makeRouter("classify")->name(), "classify");
	CClassifyingRouter r;
	EXPECT_THROW(r.validate({{-2, {1, 1}}}, "t"), std::runtime_error);
	EXPECT_THROW(r.validate({{3, {1, 1}}, {3, {2, 2}}}, "t"), std::runtime_error);
	EXPECT_NO_THROW(r.validate({{-1, {1, 1}}, {-1, {2, 2}}, {3, {1, 1}}}, "t"));
	EXPECT_THROW(r.route(0, {{0, {1, 1}}}, kNone), std::logic_error) << "no context";
	r.setContext(TRouterContext());
	const TRoutedStep out = r.route(0, {{-1, {1, 1}}, {0, {2, 1}}}, kNone);
	EXPECT_EQ(out.skipped_unknown_id, 1u) << "ID -1: skipped and counted, never silently";
	EXPECT_EQ(out.candidates, 1u);
	EXPECT_EQ(out.readings.size(), 2u);
}
