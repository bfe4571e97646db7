/** dynslam-bench: BM_LongRoute, the per-step time on a route that never revisits, against the
 * size of the map (doc/results/performance.md). The map of N landmarks is pre-built (step 0 reports
 * N landmarks behind the start, never seen again); then the ego drives the straight track into new
 * land: a landmark every 3 m, range 30 m (20 in view), 2 objects in convoy, K = 1, no drops,
 * so the map keeps growing by ~2 landmarks per 3 steps. After 11 untimed steps (step 0 and
 * 10 more) each benchmark iteration times one step (processActionObservation only). The filter is
 * kept across repetitions (one at a time: at 10,000 landmarks the covariance is 3.2 GB). */
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include "bench_setup.h"
#include "synthetic_world.h"

using namespace dynslam_bench;

namespace
{
using Clock = std::chrono::steady_clock;

TSyntheticOptions routeOptions(int prebuilt)
{
	TSyntheticOptions o;
	o.track = TSyntheticOptions::Track::Straight;
	o.spacing = 3;
	o.step_length = 2;
	o.range = 30;
	o.max_visible = 20;
	o.objects = 2;
	o.prebuilt = prebuilt;
	return o;
}

struct TRoute
{
	int landmarks = -1, engine = -1;
	std::unique_ptr<CSyntheticWorld> world;
	std::unique_ptr<dynslam::CDynamicKFSLAM2D> filter;
	void step()
	{
		mrpt::obs::CActionCollection::Ptr a;
		mrpt::obs::CSensoryFrame::Ptr sf;
		world->next(a, sf);
		filter->processActionObservation(a, sf);
	}
};

/** engine: 1 = sparse (the full EKF), 2 = compressed. */
TRoute& route(int landmarks, int engine, int warmSteps, bool fresh = false)
{
	static TRoute r;
	if (!fresh && r.landmarks == landmarks && r.engine == engine && r.filter) return r;
	r.filter.reset();
	const TSyntheticOptions o = routeOptions(landmarks);
	r.landmarks = landmarks;
	r.engine = engine;
	r.world = std::make_unique<CSyntheticWorld>(o);
	r.filter = std::make_unique<dynslam::CDynamicKFSLAM2D>();
	configureDynamic(*r.filter, o.Sigma_v, o.Sigma_w, true);
	r.filter->options.compressed_static_update = engine == 2;
	r.filter->reset();
	for (int k = 0; k < warmSteps; ++k) r.step();
	return r;
}

/** Args: landmarks of the pre-built map, engine (1 = sparse, 2 = compressed). */
void BM_LongRoute(benchmark::State& state)
{
	const int engine = int(state.range(1));
	const int n = int(state.range(0));
	TRoute& r = route(n, engine, engine == 1 && n >= 10000 ? 2 : 11);
	for (auto _ : state)
	{
		mrpt::obs::CActionCollection::Ptr a;
		mrpt::obs::CSensoryFrame::Ptr sf;
		r.world->next(a, sf);
		const auto t0 = Clock::now();
		r.filter->processActionObservation(a, sf);
		state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
	}
	state.counters["working_dim"] = double(r.filter->workingDim());
	state.counters["passive_landmarks"] = double(r.filter->passiveLandmarks());
	state.counters["route_step"] = double(r.world->step());
	state.SetLabel(engine == 2 ? "compressed" : "sparse");
}
// A fixed number of steps per repetition, so the map stays near its nominal size: 20 (the map
// grows by ~14 landmarks per repetition); 2 for the full EKF at 10,000 landmarks (~a minute
// per step), which is also warmed up by 2 steps only (its cost does not depend on the route).
BENCHMARK(BM_LongRoute)
    ->ArgsProduct({{100, 1000, 10000}, {2}})
    ->ArgsProduct({{100, 1000}, {1}})
    ->Iterations(20)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LongRoute)
    ->Args({10000, 1})
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

/** The compressed engine's global update (the getters' price) after the route of BM_LongRoute
 * (11 + 40 steps), timed once per repetition on a fresh filter. Arg: landmarks. */
void BM_LongRouteGlobalUpdate(benchmark::State& state)
{
	for (auto _ : state)
	{
		state.PauseTiming();
		TRoute& r = route(int(state.range(0)), 2, 51, true);
		state.ResumeTiming();
		const auto t0 = Clock::now();
		r.filter->globalUpdate();
		state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
	}
	state.SetLabel("compressed, global update");
}
BENCHMARK(BM_LongRouteGlobalUpdate)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
}  // namespace
