/** classify_static_test (doc/results/classification.md): with `map` a static track's reading is
 * tested with the filter's own innovation (TRouterContext::static_innovation) instead of the
 * robot-frame static filter; without a landmark in the state (the callback says no) the robot-frame
 * test stays. Synthetic tracks with a fake innovation callback. */
#include <dynslam/estimator/classifying_router.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "router_synth.h"

using namespace dynslam;
using namespace dynslam::estimator;
using router_test::TSynth;

namespace
{
/** Track 0, a point at `p` moving by v per step from step 10, a known landmark from step 2;
 * the innovation callback (if `answers`) reports nu = (bad, 0) with S = 0.01 I from step
 * `badFrom` on and nu = 0 before. Returns the step at which it turned moving (-1: never). */
int reclassifiedAt(TClassifyParams::StaticTest test, bool answers, double bad, int badFrom,
                   const Eigen::Vector2d& v)
{
	TSynth s(7);
	TClassifyParams p;
	p.static_test = test;
	CClassifyingRouter r(p);
	Eigen::Vector2d f(12, 4);
	for (int k = 0; k < 40; ++k)
	{
		TRouterContext c = s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move());
		if (answers)
			c.static_innovation =
			    [k, bad, badFrom](int32_t id, const Eigen::Vector2d&, TStaticInnovation& o)
			{
				EXPECT_EQ(id, 0);
				o.nu = Eigen::Vector2d(k >= badFrom ? bad : 0.0, 0);
				o.S = Eigen::Matrix2d::Identity() * 0.01;
				return true;
			};
		r.setContext(c);
		if (k >= 10) f += v;
		const TRoutedStep out = r.route(k, {{0, s.see(f)}}, [&](int32_t) { return k > 1; });
		if (!out.converted.empty()) return k;
	}
	return -1;
}
}  // namespace

TEST(ClassifyStaticTest, MapInnovationDecidesTheReclassification)
{
	using T = TClassifyParams::StaticTest;
	const Eigen::Vector2d still(0, 0), drives(0.5, 0);
	// A point that stays: the robot-frame filter keeps it static.
	EXPECT_EQ(reclassifiedAt(T::Robot, true, 1.0, 20, still), -1);
	// The filter's innovation says it moved from step 20 (NIS 100): reclassified after
	// reclassify_count = 3 readings beyond the gate.
	EXPECT_EQ(reclassifiedAt(T::Map, true, 1.0, 20, still), 22);
	// NIS 9 is within the 0.999 gate (13.8): stays static.
	EXPECT_EQ(reclassifiedAt(T::Map, true, 0.3, 20, still), -1);
	// A point that drives off at step 10: the robot-frame test reclassifies it ...
	const int robot = reclassifiedAt(T::Robot, true, 0.0, 0, drives);
	EXPECT_GE(robot, 10);
	EXPECT_LE(robot, 16);
	// ... the map test follows the filter's innovation (here: always consistent) instead ...
	EXPECT_EQ(reclassifiedAt(T::Map, true, 0.0, 0, drives), -1);
	// ... and falls back to the robot-frame test without a landmark in the state.
	EXPECT_EQ(reclassifiedAt(T::Map, false, 0.0, 0, drives), robot);
}

// chiSquareQuantile remembers the normal quantile of its last few probabilities (the router's
// hot path, doc/results/performance.md 14): the values must not depend on what was asked before.
// Reference values: the Wilson-Hilferty formula with the standard normal quantiles
// z(0.99) = 2.326347874, z(0.999) = 3.090232306, z(0.9) = 1.281551566.
TEST(ClassifyStaticTest, ChiSquareQuantileIsTheSameWhateverWasAskedBefore)
{
	const auto wh = [](double z, double k)
	{
		const double c = 2 / (9 * k), t = 1 - c + z * std::sqrt(c);
		return k * t * t * t;
	};
	const double z99 = 2.326347874, z999 = 3.090232306, z90 = 1.281551566;
	const std::vector<double> ps{0.99, 0.999, 0.9, 0.5, 0.95, 0.75, 0.99, 0.9, 0.999};
	for (int round = 0; round < 3; ++round)
		for (const double p : ps)
		{
			const double q = chiSquareQuantile(p, 5);
			// 0.95 and 0.75 only fill the cache's slots in between
			const double z = p == 0.99    ? z99
			                 : p == 0.999 ? z999
			                 : p == 0.9   ? z90
			                 : p == 0.5   ? 0.0
			                              : std::nan("");
			if (!std::isnan(z))
			{
				EXPECT_NEAR(q, wh(z, 5), p == 0.5 ? 1e-9 : 1e-7) << "p " << p;
			}
		}
	EXPECT_NEAR(chiSquareQuantile(0.99, 2), -2 * std::log(0.01), 1e-12);
}
