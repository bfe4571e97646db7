/** dynslam-bench: the highway run, the side-by-side comparison with MRPT's static EKF, the live
 * merge (BM_ClutterMerge), and the 225-run Monte Carlo. */
#include <benchmark/benchmark.h>
#include <dynslam/sim/scenario.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <atomic>
#include <string>
#include <thread>

#include "bench_setup.h"

using namespace dynslam_bench;

namespace
{
/** One full run of the shipped highway rawlog (121 steps). Arg: 0 = MRPT update, 1 = sparse,
 * 2 = compressed (static_update = compressed; the final global update included), 3 = sparse
 * with feature_labels = classify (issue 12: what classification costs), 4 = sparse with
 * object_model = cv and the shipped cv_* keys of config/compare_tunnel.ini, setting B of
 * doc/results/results.md 4.3.1 (issue 13: what the object-centric model costs; cv_accel_psd = [1e-6
 * 1e-6 1e-8], cv_gate = 0.5, no fallback), 5 = the tight noise of doc/results/results.md 4.8
 * (cv_accel_psd = [1e-7 1e-7 1e-9], cv_gate = 0.999; setting D without its Schmidt delay, whose key
 * cv_ego_velocity_std was removed on 2026-11-28), 6 = setting E of doc/results/results.md 4.10 (5
 * with prior_gauge = anchor), 7 = the paper's objects with prior_gauge = anchor (the output term's
 * cost: only getEgoPose per step). */
void BM_HighwayRun(benchmark::State& state)
{
	const TRun& run = highwayRun();
	const bool sparse = state.range(0) != 0;
	for (auto _ : state)
	{
		dynslam::CDynamicKFSLAM2D f;
		configureDynamic(f, run.Sigma_v, run.Sigma_0, sparse);
		if (state.range(0) == 2)
		{
			f.options.compressed_static_update = true;
			f.reset();
		}
		if (state.range(0) == 3)  // sparse, no ID oracle (issue 12: feature_labels = classify)
		{
			f.options.feature_labels = "classify";
			f.options.validate();
			f.reset();
		}
		if (state.range(0) >= 4 && state.range(0) <= 6)  // object_model = cv: B (4), D (5), E (6)
		{
			const bool d = state.range(0) >= 5;
			f.options.object_model = "cv";
			f.options.cv.dt = 0.5;
			f.options.cv.accel_psd =
			    d ? Eigen::Vector3d(1e-7, 1e-7, 1e-9) : Eigen::Vector3d(1e-6, 1e-6, 1e-8);
			f.options.cv.velocity_prior_std = Eigen::Vector3d(0.5, 0.5, 0.05);
			f.options.cv_gate = d ? 0.999 : 0.5;
			f.options.validate();
			f.reset();
		}
		if (state.range(0) >= 6)  // the anchored prior (E: 6, paper objects: 7)
		{
			f.options.prior_gauge_anchor = true;
			f.reset();
		}
		for (size_t k = 0; k < run.actions.size(); ++k)
		{
			f.processActionObservation(run.actions[k], run.frames[k]);
			benchmark::DoNotOptimize(f.getEgoPose().cov(0, 0));  // the reported ego pose
		}
		benchmark::DoNotOptimize(f.fullMean()[0]);
	}
	state.counters["steps"] = double(run.actions.size());
	const char* labels[] = {"mrpt",      "sparse",      "compressed",  "sparse+classify",
	                        "sparse+cv", "sparse+cv D", "sparse+cv E", "sparse+anchor"};
	state.SetLabel(labels[state.range(0)]);
}
BENCHMARK(BM_HighwayRun)->DenseRange(0, 7)->Unit(benchmark::kMillisecond);

/** classify_merge_live off (0) and on (1): config/highway_clutter.ini (121 steps, 3 cars, the
 * clutter that splits them into 7 objects) simulated in memory, feature_labels = classify with
 * object_model = cv and the keys of LiveMerge.ClutterHighway (3 live merges with the key on;
 * doc/results/classification.md "Merging two live objects"). */
void BM_ClutterMerge(benchmark::State& state)
{
	const TRun& run = simulatedRun("highway_clutter.ini", -1, 1);
	mrpt::config::CConfigFileMemory cfg(
	    "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-5 1e-5]\n"
	    "motion_noise = action\nSigma_0 = [1e-5 1e-5 1e-7]\nSigma_xi = [0.1 0.1]\n"
	    "feature_labels = classify\nobject_model = cv\n[ObjectModel]\ncv_dt = 0.5\n"
	    "cv_accel_psd = [0.1 0.1 1e-3]\ncv_velocity_prior_std = [0.5 0.5 0.05]\n"
	    "[Classify]\nclassify_merge_live = " +
	    std::string(state.range(0) ? "true" : "false") +
	    "\n[DynamicKFSLAM_KalmanFilter]\nmethod = kfEKFNaive\n");
	size_t objects = 0;
	for (auto _ : state)
	{
		dynslam::CDynamicKFSLAM2D f;
		f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
		f.loadOptions(cfg, "DynamicKFSLAM");
		f.KF_options.enable_profiler = false;
		for (size_t k = 0; k < run.actions.size(); ++k)
		{
			f.processActionObservation(run.actions[k], run.frames[k]);
			benchmark::DoNotOptimize(f.getEgoPose().cov(0, 0));
		}
		objects = f.router().registry().objects().size();
	}
	state.counters["steps"] = double(run.actions.size());
	state.counters["objects"] = double(objects);
	state.SetLabel(state.range(0) ? "classify+cv, merge_live on" : "classify+cv, merge_live off");
}
BENCHMARK(BM_ClutterMerge)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);

/** The same static-only run through MRPT's CRangeBearingKFSLAM2D (filter 0) and the dynamic EKF
 * with MRPT's update (1), the sparse one (2) or the compressed EKF (3, static_update =
 * compressed, the pose getter only: no global update). Args: filter, landmarks (highway_static
 * with num_landmarks overridden). Time per run; per step = run / steps. */
void BM_StaticRun(benchmark::State& state)
{
	const int filter = int(state.range(0));
	const TRun& run = simulatedRun("highway_static_scenario.ini", int(state.range(1)), 1);
	for (auto _ : state)
	{
		mrpt::slam::CRangeBearingKFSLAM2D rb;
		dynslam::CDynamicKFSLAM2D dyn;
		configureAlike(rb, dyn, run.std_range, run.std_yaw, filter >= 2);
		if (filter == 3)
		{
			dyn.options.compressed_static_update = true;
			dyn.reset();
		}
		for (size_t k = 0; k < run.actions.size(); ++k)
		{
			auto a = run.actions[k];
			auto sf = run.frames[k];
			if (filter == 0)
				rb.processActionObservation(a, sf);
			else
				dyn.processActionObservation(run.actions[k], run.frames[k]);
		}
		mrpt::poses::CPosePDFGaussian pose;
		if (filter == 0)
			rb.getCurrentRobotPose(pose);
		else
			pose = dyn.getEgoPose();
		benchmark::DoNotOptimize(pose.mean.x());
	}
	state.counters["steps"] = double(run.actions.size());
	const char* labels[] = {"CRangeBearingKFSLAM2D", "dynamic/mrpt", "dynamic/sparse",
	                        "dynamic/compressed"};
	state.SetLabel(labels[filter]);
}
BENCHMARK(BM_StaticRun)->ArgsProduct({{0, 1, 2, 3}, {80, 400}})->Unit(benchmark::kMillisecond);

/** The Monte Carlo of the paper: 9 noise levels x 25 noise seeds = 225 highway runs, each
 * simulated in memory and filtered (dynamic EKF, sparse update), on Arg(0) threads. Wall time. */
void BM_MonteCarlo225(benchmark::State& state)
{
	const int threads = int(state.range(0));
	const bool includeSim = state.range(1) != 0;
	const char* levels[] = {"w1v1", "w1v2", "w1v3", "w2v1", "w2v2", "w2v3", "w3v1", "w3v2", "w3v3"};
	const auto base = dynslam::sim::loadScenario(DYNSLAM_SOURCE_DIR "/config/highway.ini");
	// Pre-simulated runs for the filter-only variant.
	std::vector<dynslam::sim::TScenarioOptions> opts;
	std::vector<dynslam::io::TGroundTruth> gts;
	for (const char* l : levels)
	{
		auto o = base;
		o.setNoiseLevel(l);
		opts.push_back(o);
		gts.push_back(dynslam::sim::buildGroundTruth(o));
	}
	std::vector<dynslam::sim::TSimulatedRun> pre;
	if (!includeSim)
		for (int r = 0; r < 225; ++r)
			pre.push_back(
			    dynslam::sim::simulateMeasurements(gts[r / 25], opts[r / 25], 1 + r % 25));
	for (auto _ : state)
	{
		std::atomic<int> next{0};
		auto worker = [&]
		{
			for (int r; (r = next++) < 225;)
			{
				const auto& o = opts[r / 25];
				dynslam::sim::TSimulatedRun sim =
				    includeSim ? dynslam::sim::simulateMeasurements(gts[r / 25], o, 1 + r % 25)
				               : pre[r];
				dynslam::CDynamicKFSLAM2D f;
				configureDynamic(f, o.Sigma_v, o.Sigma_0, true);
				for (size_t k = 0; k < sim.actions.size(); ++k)
					f.processActionObservation(sim.actions[k], sim.frames[k]);
				benchmark::DoNotOptimize(f.fullMean()[0]);
			}
		};
		std::vector<std::thread> pool;
		for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
		for (auto& t : pool) t.join();
	}
	state.SetLabel(std::string(includeSim ? "simulate+filter" : "filter only") + ", " +
	               std::to_string(threads) + " thread(s)");
}
BENCHMARK(BM_MonteCarlo225)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
}  // namespace
