/** Bounded bookkeeping (issue 29, item 3): on the soak world (bench/soak_world.h: every
 * landmark re-identified each lap, 10 % missed detections, 2 clutter readings per step with
 * fresh IDs) the classifying router's per-step work must not grow with the run. Counted, not
 * timed (the time per step is BM_Soak's, doc/results/performance.md section 18):
 *  - the tracks its per-step prediction visits are at most the tracks read in the last
 *    forget_steps + 1 steps (before: every track ever read, 20,000 steps: 22 x the time per step);
 *  - the -1 association carries no track the router has forgotten (before: every clutter
 *    reading ever, two per step). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/classifying_router.h>
#include <gtest/gtest.h>

#include <deque>
#include <set>

#include "soak_world.h"

using namespace dynslam;

TEST(BoundedBookkeeping, ClassifyingRouterVisitsOnlyRecentTracksAndForgetsClutter)
{
	dynslam_bench::TSoakOptions o;
	o.objects = 0;  // static landmarks and clutter: the map is bounded by the drop keys
	dynslam_bench::CSoakWorld world(o);
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0.setZero();
	f.options.motion_noise_from_action = true;
	f.options.feature_labels = "classify";
	f.options.prune_min_sightings = 3;
	f.options.prune_window = 5;
	f.options.drop_static_after_unseen_steps = 20;
	f.options.record_dropped = false;
	f.options.validate();
	f.reset();
	const auto* router = dynamic_cast<const estimator::CClassifyingRouter*>(&f.router());
	ASSERT_NE(router, nullptr);
	const int forget = router->params().forget_steps;

	const int steps = 3000;                // 5 laps of 600 steps
	std::deque<std::set<int32_t>> recent;  // the IDs read in the last forget + 1 steps
	size_t maxLive = 0;
	for (int k = 0; k < steps; ++k)
	{
		mrpt::obs::CActionCollection::Ptr a;
		mrpt::obs::CSensoryFrame::Ptr sf;
		world.next(a, sf);
		std::set<int32_t> ids;
		for (const auto& m :
		     sf->getObservationByClass<mrpt::obs::CObservationBearingRange>()->sensedData)
			ids.insert(m.landmarkID);
		recent.push_back(ids);
		if (int(recent.size()) > forget + 1) recent.pop_front();
		ASSERT_NO_THROW(f.processActionObservation(a, sf)) << "step " << k;
		std::set<int32_t> window;
		for (const auto& s : recent) window.insert(s.begin(), s.end());
		ASSERT_LE(router->liveTrackCount(), window.size()) << "step " << k;
		maxLive = std::max(maxLive, router->liveTrackCount());
		ASSERT_LE(router->carriedTrackCount(), router->tracks().size()) << "step " << k;
	}
	// Every landmark read was re-identified 4 times and 6,000 clutter IDs were read: the router
	// still knows the landmarks' tracks (a static track read again keeps its class), but the
	// clutter candidates are forgotten, and the per-step work is the view's.
	EXPECT_GE(world.lap(), 4);
	EXPECT_EQ(world.clutterReadings(), 2 * steps);
	EXPECT_LT(router->tracks().size(), size_t(world.clutterReadings()) / 2);
	EXPECT_LT(maxLive, size_t(o.landmarks));
	std::cout << "tracks known " << router->tracks().size() << ", carried "
	          << router->carriedTrackCount() << ", largest live " << maxLive << "\n";
}
