/** dynslam-bench: per-step time against the state size, the number of objects and the number
 * of steps (synthetic_world.h). Manual timing: only processActionObservation is timed, the
 * generation of the step is not. */
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>

#include "bench_setup.h"
#include "synthetic_world.h"

using namespace dynslam_bench;

namespace
{
using Clock = std::chrono::steady_clock;

/** A filter plus its world, warmed up once and kept across repetitions (the state size stays
 * constant on the ring once every landmark is in the map). */
struct TWarm
{
	std::unique_ptr<CSyntheticWorld> world;
	std::unique_ptr<dynslam::CDynamicKFSLAM2D> filter;
};

TWarm& warmRing(int landmarks, int objects, bool sparse)
{
	static std::map<std::tuple<int, int, bool>, TWarm> cache;
	TWarm& w = cache[{landmarks, objects, sparse}];
	if (!w.filter)
	{
		TSyntheticOptions o;
		o.landmarks = landmarks;
		o.objects = objects;
		o.first_step_sees_all = true;
		w.world = std::make_unique<CSyntheticWorld>(o);
		w.filter = std::make_unique<dynslam::CDynamicKFSLAM2D>();
		configureDynamic(*w.filter, o.Sigma_v, o.Sigma_w, sparse);
		for (int k = 0; k < 3; ++k)
		{
			mrpt::obs::CActionCollection::Ptr a;
			mrpt::obs::CSensoryFrame::Ptr sf;
			w.world->next(a, sf);
			w.filter->processActionObservation(a, sf);
		}
	}
	return w;
}

void timeSteps(benchmark::State& state, TWarm& w)
{
	for (auto _ : state)
	{
		mrpt::obs::CActionCollection::Ptr a;
		mrpt::obs::CSensoryFrame::Ptr sf;
		w.world->next(a, sf);
		const auto t0 = Clock::now();
		w.filter->processActionObservation(a, sf);
		state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
	}
	state.counters["state_dim"] = double(w.filter->fullMean().size());
}

/** Per step against the number of static landmarks in the state (all of them; 20 observed per
 * step). Args: landmarks, update (0 = MRPT, 1 = sparse). */
void BM_StepVsLandmarks(benchmark::State& state)
{
	const bool sparse = state.range(1) != 0;
	timeSteps(state, warmRing(int(state.range(0)), 0, sparse));
	state.SetLabel(sparse ? "sparse" : "mrpt");
}
BENCHMARK(BM_StepVsLandmarks)
    ->ArgsProduct({{10, 30, 100, 300, 1000, 2000}, {1}})
    ->ArgsProduct({{10, 30, 100, 300}, {0}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

/** Per step against the number of moving objects (3 features each, all seen every step, 50
 * static landmarks). Args: objects, update. */
void BM_StepVsObjects(benchmark::State& state)
{
	const bool sparse = state.range(1) != 0;
	timeSteps(state, warmRing(50, int(state.range(0)), sparse));
	state.SetLabel(sparse ? "sparse" : "mrpt");
}
BENCHMARK(BM_StepVsObjects)
    ->ArgsProduct({{1, 3, 10, 30, 100}, {0, 1}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

/** Mean per-step time of a whole run of Arg(0) steps on the endless straight track (2 objects),
 * with old object poses dropped (K = 1) and static landmarks unseen for 5 steps dropped.
 * Counters: mean of the last 10% of the steps, the final state size, the RSS growth. */
void BM_StepVsSteps(benchmark::State& state)
{
	const int steps = int(state.range(0));
	const bool sparse = state.range(1) != 0;
	double lastTenth = 0, dim = 0, rssGrowth = 0;
	for (auto _ : state)
	{
		TSyntheticOptions o;
		o.track = TSyntheticOptions::Track::Straight;
		o.spacing = 10;
		o.step_length = 5;
		o.objects = 2;
		CSyntheticWorld world(o);
		dynslam::CDynamicKFSLAM2D f;
		configureDynamic(f, o.Sigma_v, o.Sigma_w, sparse);
		f.options.drop_static_after_unseen_steps = 5;
		const long rss0 = currentRssKb();
		double total = 0, tail = 0;
		for (int k = 0; k < steps; ++k)
		{
			mrpt::obs::CActionCollection::Ptr a;
			mrpt::obs::CSensoryFrame::Ptr sf;
			world.next(a, sf);
			const auto t0 = Clock::now();
			f.processActionObservation(a, sf);
			const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
			total += dt;
			if (k >= steps - steps / 10) tail += dt;
		}
		state.SetIterationTime(total / steps);
		lastTenth = tail / (steps / 10);
		dim = double(f.fullMean().size());
		rssGrowth = double(currentRssKb() - rss0);
	}
	state.counters["last10pct_us"] = lastTenth * 1e6;
	state.counters["state_dim"] = dim;
	state.counters["rss_growth_kB"] = rssGrowth;
	state.SetLabel(sparse ? "sparse, time = mean per step" : "mrpt, time = mean per step");
}
BENCHMARK(BM_StepVsSteps)
    ->ArgsProduct({{100, 1000, 10000, 100000}, {0, 1}})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMicrosecond);
}  // namespace
