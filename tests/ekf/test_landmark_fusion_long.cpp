/** The measurement of doc/robustness.md "Fusing re-identified landmarks" (not part of the suite:
 * DISABLED_, minutes per seed; run with
 *   ekf_fusion_tests --gtest_also_run_disabled_tests --gtest_filter='*Long*'):
 * a generated circle (150 m radius, one lap = 188 steps, 300 true landmarks, 8 cars, 4
 * pedestrians, 2 rotating objects) for 600 steps (or DYNSLAM_FUSION_LONG_STEPS) with 10 % missed
 * detections, 2 clutter readings per step, track breaks (probability 0.01 per reading; after 4
 * unseen steps, so every landmark comes back under a new ID on each lap), pruning k = 3, W = 5; the
 * EKF without and with fuse_landmarks_prob = 0.99: map size vs the truth, wrong fusions, ego ATE,
 * time per step. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/clutter_runs.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>

using namespace dynslam;

namespace
{
/** The steps: 600, or the environment's DYNSLAM_FUSION_LONG_STEPS. */
std::string steps()
{
	const char* e = std::getenv("DYNSLAM_FUSION_LONG_STEPS");
	return e ? e : "600";
}

sim::TScenarioOptions longScenario(uint32_t seed)
{
	return sim::loadScenarioFromText(
	    "[Scenario]\ntype = generated\nname = fusion_long\ndt = 0.5\nsteps = " + steps() +
	    "\nworld_seed = " + std::to_string(seed) + "\nnoise_seed = " + std::to_string(seed + 100) +
	    "\n[Sensor]\nrange = 40\n[Noise]\nlevel = w2v2\n"
	    "[Generated]\ntrack_radius = 150\nego_speed = 10\nnum_landmarks = 300\n"
	    "landmark_offset_min = 3\nlandmark_offset_max = 30\nnum_cars = 8\nnum_pedestrians = 4\n"
	    "num_rotating = 2\nobject_spread = 40\n"
	    "[Effects]\nmissed_detection_probability = 0.1\nclutter_per_step = 2\n"
	    "track_break_probability = 0.01\ntrack_break_gap = 4\n");
}

struct TRun
{
	double ate = 0, msAll = 0, msFirst = 0, msLast = 0;
	size_t fused = 0, live = 0;
	std::vector<estimator::TFusionPair> fusions;
};

TRun run(const sim::TSimulatedRun& s, const io::TGroundTruth& gt, const std::string& extra)
{
	mrpt::config::CConfigFileMemory ini(
	    dynslam_test::highwayFilterIni("prune_min_sightings = 3\nprune_window = 5\n" + extra));
	CDynamicKFSLAM2D ekf;
	ekf.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	ekf.loadOptions(ini, "DynamicKFSLAM");
	TRun r;
	const size_t n = s.actions.size(), tenth = n / 10;
	r.ate = dynslam_test::runSteps(ekf, s, gt,
	                               [&](size_t k, double ms)
	                               {
		                               r.msAll += ms / double(n);
		                               if (k >= 100 && k < 200) r.msFirst += ms / 100;
		                               if (k >= n - tenth) r.msLast += ms / double(tenth);
		                               r.fused += ekf.getLastStepReport().fused_static;
	                               });
	r.live = ekf.getStaticLandmarks().size();
	r.fusions = ekf.getFusedLandmarks();
	return r;
}
}  // namespace

TEST(LandmarkFusionLong, DISABLED_GeneratedCircleWithBreaksClutterAndMisses)
{
	for (const uint32_t seed : {1u, 2u, 3u})
	{
		const sim::TScenarioOptions o = longScenario(seed);
		const io::TGroundTruth gt = sim::buildGroundTruth(o);
		const sim::TSimulatedRun s = sim::simulateMeasurements(gt, o, o.noise_seed);
		std::map<int32_t, int32_t> trueOf;
		std::set<int32_t> trueSeen;
		for (const auto& c : s.classes)
		{
			if (c.cls == io::TrueClass::Moving) continue;
			trueOf[c.id] = c.cls == io::TrueClass::Static ? c.true_id : -1;
			if (c.cls == io::TrueClass::Static) trueSeen.insert(c.true_id);
		}
		const TRun off = run(s, gt, ""), on = run(s, gt, "fuse_landmarks_prob = 0.99\n");
		size_t wrong = 0;
		for (const auto& f : on.fusions)
			wrong += !(trueOf.at(f.keep) >= 0 && trueOf.at(f.keep) == trueOf.at(f.gone));
		const double t = double(trueSeen.size());
		std::cout << "world_seed " << seed << ", noise_seed " << seed + 100 << " ("
		          << s.actions.size() << " steps): true landmarks seen " << trueSeen.size()
		          << ", static IDs " << trueOf.size() << "; final map without fusion " << off.live
		          << " (" << off.live / t << " x), with " << on.live << " (" << on.live / t
		          << " x); fused " << on.fused << ", wrong " << wrong << "; ATE " << off.ate
		          << " -> " << on.ate << " m (" << on.ate / off.ate
		          << " x); ms/step (all, 100-200, "
		          << "last tenth) " << off.msAll << " " << off.msFirst << " " << off.msLast
		          << " -> " << on.msAll << " " << on.msFirst << " " << on.msLast << "\n";
		EXPECT_EQ(wrong, 0u);
	}
}
