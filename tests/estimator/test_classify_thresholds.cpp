/** The decision thresholds of the classifying router (classifying_router.h) on both sides of
 * their boundaries, with noiseless literal readings and expected values computed by hand
 * (issue 32, "Test gaps to close"):
 * - Wald's SPRT with unequal error rates: the moving bound log((1 - beta) / alpha) and the static
 *   bound log(beta / (1 - alpha)), each crossed and not crossed by the evidence of one sighting;
 * - the forced decision at the max_window-th sighting and its side (the sign of the sum);
 * - rigid grouping: the chi-square quantile with n - 1 dof (n common steps) and group_max_dist.
 *
 * The scene: the robot stands still (u = 0, U = 0), the Cartesian model, R = r I. A candidate's
 * static filter then stays isotropic: its first reading starts it at (z, c = r); the next
 * reading, one step later, has the innovation nu = z - p with covariance s I, s = c + r, and
 * adds the log-likelihood ratio
 *   0.5 |nu|^2 (1 / s - 1 / (s + q)) - log((s + q) / s),   q = motion_std^2,
 * then p += (c / s) nu, c = c r / s. */
#include <dynslam/estimator/classifying_router.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

using namespace dynslam::estimator;

namespace
{
const auto kNone = [](int32_t) { return false; };

/** A router on a still robot with R = r I; step k routes readings[k] (track i = reading i). */
struct TStill
{
	CClassifyingRouter router;
	double r;
	int step = 0;
	TStill(const TClassifyParams& p, double r_) : router(p), r(r_) {}
	void see(const std::vector<Eigen::Vector2d>& zs)
	{
		TRouterContext c;
		c.R = r * Eigen::Matrix2d::Identity();
		router.setContext(c);
		std::vector<TReading> rd;
		for (size_t i = 0; i < zs.size(); ++i) rd.push_back({int32_t(i), zs[i]});
		router.route(step++, rd, kNone);
	}
	const TTrack& track(int32_t id) const { return router.tracks().at(id); }
};

TClassifyParams rates(double alpha, double beta, double motion_std)
{
	TClassifyParams p;
	p.alpha = alpha;
	p.beta = beta;
	p.motion_std = motion_std;
	return p;
}
}  // namespace

// alpha = 0.01, beta = 0.1: decide moving at log(0.9 / 0.01) = log 90 = 4.4998, static at
// log(0.1 / 0.99) = -2.2925. With the rates swapped the bounds would be log 9.9 = 2.2925 and
// log(0.01 / 0.9) = -4.4998.
TEST(ClassifyThresholds, SprtBoundsWithUnequalErrorRates)
{
	const CClassifyingRouter r(rates(0.01, 0.1, 1.0));
	EXPECT_NEAR(r.upperThreshold(), std::log(90.0), 1e-12);
	EXPECT_NEAR(r.lowerThreshold(), std::log(0.1 / 0.99), 1e-12);
}

TEST(ClassifyThresholds, MovingBoundOfTheSprtWithUnequalErrorRates)
{
	// r = 0.5 (s = 1 at the second sighting), motion_std = 1 (q = 1): LLR = 0.25 |nu|^2 - log 2.
	// |nu| = 4.5: 4.3694, between log 9.9 and log 90: undecided (swapped rates: moving).
	// |nu| = 4.6: 4.5969 >= log 90: moving.
	for (const double jump : {4.5, 4.6})
	{
		TStill s(rates(0.01, 0.1, 1.0), 0.5);
		s.see({{10, 0}});
		s.see({{10 + jump, 0}});
		const double llr = 0.25 * jump * jump - std::log(2.0);
		EXPECT_NEAR(s.track(0).llr, llr, 1e-12) << jump;
		EXPECT_EQ(s.track(0).cls, jump == 4.5 ? TrackClass::Candidate : TrackClass::Moving)
		    << "jump " << jump << ", LLR " << llr << ", bound " << std::log(90.0);
	}
}

TEST(ClassifyThresholds, StaticBoundOfTheSprtWithUnequalErrorRates)
{
	// The same reading twice (nu = 0), s = 1: LLR = -log(1 + q).
	// q = 9.5: -log 10.5 = -2.3514 <= log(0.1 / 0.99) = -2.2925: static (swapped rates:
	// undecided, above -4.4998). q = 8.5: -log 9.5 = -2.2513: undecided.
	for (const double q : {9.5, 8.5})
	{
		TStill s(rates(0.01, 0.1, std::sqrt(q)), 0.5);
		s.see({{10, 0}});
		s.see({{10, 0}});
		EXPECT_NEAR(s.track(0).llr, -std::log(1 + q), 1e-12) << q;
		EXPECT_EQ(s.track(0).cls, q == 9.5 ? TrackClass::Static : TrackClass::Candidate)
		    << "q " << q;
	}
}

// max_window = 4, bounds +-log(0.999 / 0.001) = +-6.9067 (never reached): the 4th sighting
// (step 3) forces the decision by the sign of the sum; the 3rd (step 2) leaves it undecided.
// r = 0.5, motion_std = 0.3 (q = 0.09).
TEST(ClassifyThresholds, ForcedDecisionAtTheWindowsLastSightingNegativeEvidence)
{
	TClassifyParams p = rates(1e-3, 1e-3, 0.3);
	p.max_window = 4;
	TStill s(p, 0.5);
	// Four equal readings: s = 1, 0.75, 2/3 -> LLR -log 1.09 - log 1.12 - log 1.135.
	const double llr3 = -std::log(1.09) - std::log(1.12), llr4 = llr3 - std::log(1.135);
	for (int k = 0; k < 3; ++k) s.see({{10, 0}});
	EXPECT_NEAR(s.track(0).llr, llr3, 1e-12);
	EXPECT_EQ(s.track(0).cls, TrackClass::Candidate) << "decided before the window's end";
	s.see({{10, 0}});
	EXPECT_NEAR(s.track(0).llr, llr4, 1e-12);  // -0.3261 < 0
	EXPECT_EQ(s.track(0).cls, TrackClass::Static) << "not forced at the 4th sighting";
	EXPECT_EQ(s.track(0).decided_step, 3);
}

TEST(ClassifyThresholds, ForcedDecisionAtTheWindowsLastSightingPositiveEvidence)
{
	TClassifyParams p = rates(1e-3, 1e-3, 0.3);
	p.max_window = 4;
	TStill s(p, 0.5);
	// (10, 0), (14, 0): nu = 4, s = 1: 8 (1 - 1 / 1.09) - log 1.09 = 0.5744; the filter moves to
	// (12, 0), c = 0.25; two readings there (nu = 0): -log 1.12 - log 1.135.
	const double llr2 = 8 * (1 - 1 / 1.09) - std::log(1.09);
	const double llr4 = llr2 - std::log(1.12) - std::log(1.135);
	s.see({{10, 0}});
	s.see({{14, 0}});
	EXPECT_NEAR(s.track(0).llr, llr2, 1e-12);
	s.see({{12, 0}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Candidate) << "decided before the window's end";
	s.see({{12, 0}});
	EXPECT_NEAR(s.track(0).llr, llr4, 1e-12);  // 0.3344 > 0
	EXPECT_EQ(s.track(0).cls, TrackClass::Moving) << "not forced (or forced static)";
	EXPECT_EQ(s.track(0).decided_step, 3);
}

namespace
{
/** Tracks 0 and 1 moving 0.4 m per step along x, 2 m apart along y; track 1 is e off along y at
 * the second of three sightings. Both are decided moving at the third (alpha = beta = 1e-4:
 * bound 9.21; track 0: 3.31 after the second sighting, 16.2 after the third; track 1 with
 * e <= 0.4: at most 7.31 after the second). Returns whether they form one object. */
bool grouped(double e, double groupMaxDist, std::map<int, TPoint2>* a = nullptr,
             std::map<int, TPoint2>* b = nullptr)
{
	TClassifyParams p = rates(1e-4, 1e-4, 0.1);
	p.group_max_dist = groupMaxDist;
	TStill s(p, 0.005);
	s.see({{10, 0}, {10, 2}});
	s.see({{10.4, 0}, {10.4, 2 + e}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Candidate);
	EXPECT_EQ(s.track(1).cls, TrackClass::Candidate);
	s.see({{10.8, 0}, {10.8, 2}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Moving);
	EXPECT_EQ(s.track(1).cls, TrackClass::Moving);
	if (a) *a = s.track(0).history;
	if (b) *b = s.track(1).history;
	return s.track(0).object == s.track(1).object;
}
}  // namespace

// Distances (2, 2 + e, 2), each with variance 2 r = 0.01 (g^T (R + R) g): weighted mean 2 + e/3,
// chi2 = (2 e^2 / 3) / 0.01, 3 common steps: 2 dof, quantile at 0.99 = -2 log 0.01 = 9.2103
// (1 dof: 6.63, 3 dof: 11.34). chi2 = 9.0 groups, 9.45 does not.
TEST(ClassifyThresholds, RigidGroupingChiSquareWithTwoDof)
{
	const auto eFor = [](double chi2) { return std::sqrt(chi2 * 0.015); };
	std::map<int, TPoint2> a, b;
	EXPECT_TRUE(grouped(eFor(9.0), 6, &a, &b)) << "chi2 9.0 < 9.2103 (2 dof)";
	const TRigidTest t = rigidDistanceTest(a, b);
	EXPECT_EQ(t.common, 3);
	EXPECT_NEAR(t.chi2, 9.0, 1e-9);
	EXPECT_NEAR(t.mean_dist, 2 + eFor(9.0) / 3, 1e-12);
	EXPECT_FALSE(grouped(eFor(9.45), 6, &a, &b)) << "chi2 9.45 > 9.2103 (2 dof)";
	EXPECT_NEAR(rigidDistanceTest(a, b).chi2, 9.45, 1e-9);
}

TEST(ClassifyThresholds, RigidGroupingMaxDistance)
{
	// Exactly 2 m apart at every step (chi2 = 0): grouped within 2.01 m, not within 1.99 m.
	EXPECT_TRUE(grouped(0, 2.01));
	EXPECT_FALSE(grouped(0, 1.99));
}

namespace
{
/** A track decided static at its second sighting (step 1): alpha = 0.01, beta = 0.1, r = 0.5,
 * q = 9.5 (LLR -log 10.5 < log(0.1 / 0.99)). Its filter is then at (10, 0) with c = 0.25: a
 * reading z has NIS |z - (10, 0)|^2 / 0.75 against the reclassify gate, the chi-square quantile
 * (2 dof) at 0.999, -2 log 0.001 = 13.8155: |nu| = 3.2 (NIS 13.653) is consistent, |nu| = 3.25
 * (NIS 14.083) is not. */
TStill staticTrack(int reclassifyCount)
{
	TClassifyParams p = rates(0.01, 0.1, std::sqrt(9.5));
	p.reclassify_count = reclassifyCount;
	TStill s(p, 0.5);
	s.see({{10, 0}});
	s.see({{10, 0}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Static);
	return s;
}
}  // namespace

TEST(ClassifyThresholds, ReclassifyGateOfAStaticTrack)
{
	TStill in = staticTrack(1);
	in.see({{13.2, 0}});
	EXPECT_EQ(in.track(0).cls, TrackClass::Static) << "NIS 13.653 < 13.8155 reclassified";
	EXPECT_EQ(in.track(0).bad_streak, 0);
	TStill out = staticTrack(1);
	out.see({{13.25, 0}});
	EXPECT_EQ(out.track(0).cls, TrackClass::Moving) << "NIS 14.083 > 13.8155 kept static";
	EXPECT_EQ(out.track(0).decided_step, 2);
}

TEST(ClassifyThresholds, ReclassifyCountConsecutiveReadingsBeyondTheGate)
{
	// count 3: the 3rd reading in a row beyond the gate turns it moving, not the 2nd; a reading
	// within the gate in between restarts the count. (A rejected reading leaves the filter.)
	TStill s = staticTrack(3);
	s.see({{14, 0}});
	s.see({{14, 0}});
	EXPECT_EQ(s.track(0).bad_streak, 2);
	s.see({{10, 0}});
	EXPECT_EQ(s.track(0).bad_streak, 0);
	s.see({{6, 0}});
	s.see({{6, 0}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Static) << "moving after 2 readings beyond the gate";
	s.see({{6, 0}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Moving) << "static after 3 readings beyond the gate";
	EXPECT_EQ(s.track(0).decided_step, 7);
}

TEST(ClassifyThresholds, StopCountConsecutiveStaticReadingsOfAMovingTrack)
{
	// Decided moving at step 1 (|nu| = 4.6, as above); stop_count = 2: the reading of step 2
	// starts its static filter, those of steps 3 and 4 are within the gate (the same point):
	// static at step 4, not at step 3.
	TClassifyParams p = rates(0.01, 0.1, 1.0);
	p.stop_count = 2;
	TStill s(p, 0.5);
	s.see({{10, 0}});
	s.see({{14.6, 0}});
	ASSERT_EQ(s.track(0).cls, TrackClass::Moving);
	for (int k = 2; k <= 3; ++k)
	{
		s.see({{20, 0}});
		EXPECT_EQ(s.track(0).cls, TrackClass::Moving) << "stopped at step " << k;
	}
	s.see({{20, 0}});
	EXPECT_EQ(s.track(0).cls, TrackClass::Static) << "not stopped at step 4";
	EXPECT_EQ(s.track(0).decided_step, 4);
}

TEST(ClassifyThresholds, ForgetStepsOfAnUnseenCandidate)
{
	// forget_steps = 3, the candidate last seen at step 0: kept while step - 0 <= 3, forgotten
	// at step 4. (Track 1 is seen at every step; the candidate's reading is left out.)
	TClassifyParams p;
	p.forget_steps = 3;
	TStill s(p, 0.5);
	s.see({{10, 0}, {5, 5}});
	for (int k = 1; k <= 3; ++k)
	{
		TRouterContext c;
		c.R = 0.5 * Eigen::Matrix2d::Identity();
		s.router.setContext(c);
		s.router.route(k, {{1, {5, 5}}}, kNone);
		EXPECT_EQ(s.router.tracks().count(0), 1u) << "forgotten at step " << k;
	}
	TRouterContext c;
	c.R = 0.5 * Eigen::Matrix2d::Identity();
	s.router.setContext(c);
	s.router.route(4, {{1, {5, 5}}}, kNone);
	EXPECT_EQ(s.router.tracks().count(0), 0u) << "kept at step 4";
}
