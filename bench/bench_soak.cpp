/** dynslam-bench: BM_Soak (issue 29), a long run with what a real front-end does to the
 * readings (bench/soak_world.h: a ring driven lap after lap, every landmark re-identified each
 * lap, 10 % missed detections, 2 clutter readings per step, 4 objects in convoy each replaced by
 * a new one every 200 steps) and the keys that keep the state bounded: pruning (k = 3 in W = 5),
 * static landmarks dropped after 20 unseen steps, objects after 10, record_dropped = false.
 * One iteration is the whole run (Arg: steps). Counters: mean time per step of the first and
 * the last tenth of the run and their ratio, the peak RSS of the process (getrusage: the
 * highest of every benchmark run before in the same process, so run BM_Soak alone for its own),
 * the final map (static landmarks and objects in the state) and what the world has in view. */
#include <benchmark/benchmark.h>

#include <chrono>
#include <vector>

#include "bench_setup.h"
#include "soak_world.h"

using namespace dynslam_bench;

namespace
{
using Clock = std::chrono::steady_clock;

/** The filter of BM_Soak: bench_setup's dynamic EKF with the bounding keys. */
void configureSoak(dynslam::CDynamicKFSLAM2D& f, const TSoakOptions& o, bool classify)
{
	configureDynamic(f, o.Sigma_v, Eigen::Matrix3d::Zero(), true);
	if (classify) f.options.feature_labels = "classify";
	f.options.prune_min_sightings = 3;
	f.options.prune_window = 5;
	f.options.drop_static_after_unseen_steps = 20;
	f.options.drop_object_after_unseen_steps = classify ? 0 : 10;
	f.options.record_dropped = false;
	f.options.validate();
	f.reset();
}

void BM_Soak(benchmark::State& state)
{
	const int steps = int(state.range(0));
	const bool classify = state.range(1) != 0;
	const int tenth = std::max(1, steps / 10);
	TSoakOptions o;
	if (classify) o.objects = 0;
	std::vector<double> ms(size_t(steps), 0.0);
	size_t landmarks = 0, objects = 0;
	for (auto _ : state)
	{
		CSoakWorld world(o);
		dynslam::CDynamicKFSLAM2D f;
		configureSoak(f, o, classify);
		double total = 0;
		for (int k = 0; k < steps; ++k)
		{
			mrpt::obs::CActionCollection::Ptr a;
			mrpt::obs::CSensoryFrame::Ptr sf;
			world.next(a, sf);
			const auto t0 = Clock::now();
			f.processActionObservation(a, sf);
			ms[size_t(k)] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
			total += ms[size_t(k)];
		}
		state.SetIterationTime(total * 1e-3);
		landmarks = f.staticLandmarkCount();
		objects = f.liveObjectCount();
	}
	auto mean = [&](int from, int to)
	{
		double s = 0;
		for (int k = from; k < to; ++k) s += ms[size_t(k)];
		return s / double(to - from);
	};
	const double first = mean(0, tenth), last = mean(steps - tenth, steps);
	state.counters["steps"] = double(steps);
	state.counters["ms_first_tenth"] = first;
	state.counters["ms_last_tenth"] = last;
	state.counters["last_over_first"] = last / first;
	state.counters["peak_rss_mb"] = double(peakRssKb()) / 1024.0;
	state.counters["map_landmarks"] = double(landmarks);
	state.counters["live_objects"] = double(objects);
	state.counters["true_objects"] = double(o.objects);
	state.SetLabel("ring " + std::to_string(o.landmarks) + " landmarks k=3 W=5 N=20/10");
}
// 20,000 steps: 1.4-2.9 s per run on one core of the shared 2-core machine
// (doc/results/performance.md, section 18); 2,000 for a quick look.
BENCHMARK(BM_Soak)
    ->ArgsProduct({{2000, 20000}, {0, 1}})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
}  // namespace
