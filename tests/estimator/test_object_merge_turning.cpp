/** Merging a linked object on a turning car (classify_merge_linked, doc/results/classification.md
 * "Merging a linked object"): after a merge the cv / ctrv sighting must keep the centroid of the
 * lost object's founders as its pose's centroid. Using the centroid of all its features
 * instead shifts every prediction by (I - R(theta)) (c_all - c0), theta the object's rotation
 * since its first sighting: invisible on the highway (theta ~ 0), metres on a car that has
 * turned by a few radians. A generated circle-track world (one car driving around with the ego),
 * the car unseen for a few steps (an occlusion), back under new IDs with its detection box as a
 * hint, linked and merged, then tracked while it keeps turning. */
#include <dynslam/core/models/object_motion.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <map>
#include <optional>
#include <set>

#include "object_merge_setup.h"

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
using dynslam_test::featureWorld;

/** One car on a circle of radius 60 m around with the ego (both at 8 m/s: 0.13 rad/s). */
const char* kCircle =
    "[Scenario]\ntype = generated\nname = merge_turning\ndt = 0.5\nsteps = 80\n"
    "world_seed = 3\nnoise_seed = 4\n[Sensor]\nrange = 40\n[Noise]\nlevel = w2v2\n"
    "[Generated]\ntrack_radius = 60\nego_speed = 8\nnum_landmarks = 60\n"
    "landmark_offset_min = 4\nlandmark_offset_max = 25\nnum_cars = 1\nnum_pedestrians = 0\n"
    "num_rotating = 0\nfeatures_per_car = 4\ncar_speed_factor_min = 1\n"
    "car_speed_factor_max = 1\nobject_spread = 25\n"
    "[Effects]\ntrack_break_gap = 4\ndetection_groups = true\n";
/** The car unseen in steps [40, 50): 5 s, in which it turns by 0.67 rad; the cv prediction
 * across the gap (straight in xi) then puts N's features off L's founders, so the centroid of all
 * of L's features is not its founders' (ctrv predicts the circle: both nearly equal). */
constexpr size_t kGapStart = 40, kGapEnd = 50;

struct TTurnRun
{
	size_t linked = 0, merged = 0;
	long merge_step = -1;
	/** The merged features' world positions (founders' centroid) against the truth, RMS over
	 * the steps from the second after the merge (the first update after it corrects the
	 * velocity carried across the gap: 0.22 m off then, with or without the break). */
	double feat_rmse = 0;
	size_t feat_n = 0;
};

TTurnRun runTurning(const std::string& keys)
{
	const sim::TScenarioOptions o = sim::loadScenarioFromText(kCircle);
	io::TGroundTruth gt = sim::buildGroundTruth(o);
	for (auto& og : gt.objects)
		for (size_t k = kGapStart; k < kGapEnd; ++k) og.visible[k] = 0;  // an occlusion
	const sim::TSimulatedRun sim = sim::simulateMeasurements(gt, o, o.noise_seed);
	mrpt::config::CConfigFileMemory cfg(dynslam_test::highwayFilterIni(keys));
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	TTurnRun r;
	double sf = 0;
	size_t row = 0;
	std::set<int32_t> into;
	std::map<int32_t, const io::TObjectGroundTruth*> trueObj;
	for (const auto& t : gt.objects) trueObj[t.object] = &t;
	std::map<int32_t, std::pair<int32_t, int32_t>> truthOf;  // track -> (true object, feature)
	for (size_t k = 0; k < sim.actions.size(); ++k)
	{
		ekf.processActionObservation(sim.actions[k], sim.frames[k]);
		const TRoutedStep& st = ekf.lastRoutedStep();
		for (const auto& m : st.readings)
		{
			const io::TReadingClass& c = sim.classes.at(row++);
			if (m.reading.id >= 0) truthOf[m.reading.id] = {c.object, c.feature};
		}
		r.linked += st.linked;
		r.merged += ekf.getLastStepReport().objects_merged;
		for (const auto& mg : st.merges)
			if (ekf.router().registry().has(mg.into) && !ekf.router().registry().has(mg.from))
				into.insert(mg.into), r.merge_step = long(k);
		for (const auto& m : st.readings)
		{
			if (m.route != Route::ObjectTimeT || !into.count(m.object) ||
			    long(k) < r.merge_step + 2)
				continue;
			const auto [to, tf] = truthOf.at(m.reading.id);
			if (to < 0 || tf < 0) continue;
			const auto w = featureWorld(ekf, m.object, m.reading.id);
			if (!w) continue;
			sf += (*w - trueObj.at(to)->features.at(k).col(tf)).squaredNorm();
			++r.feat_n;
		}
	}
	r.feat_rmse = r.feat_n ? std::sqrt(sf / double(r.feat_n)) : 0;
	return r;
}
}  // namespace

TEST(ObjectMergeTurning, MergedFeaturesFollowTheFoundersCentroid)
{
	// classify_motion_std = 2 m per step: the link's velocity gate must pass the car's velocity
	// turned by 0.67 rad in the gap (5.4 m/s, 2.7 m per step; with 1 m per step a gap of 8 or 10
	// steps is not linked).
	const std::string common =
	    "feature_labels = classify\n[Classify]\nclassify_use_hints = true\nclassify_merge_linked = "
	    "true\n"
	    "classify_motion_std = 2.0\n[ObjectModel]\ncv_dt = 0.5\ncv_velocity_prior_std = [0.5 0.5 "
	    "0.05]\ncv_accel_psd = [0.1 0.1 1e-3]\n";
	for (const char* model : {"cv", "ctrv"})
	{
		SCOPED_TRACE(model);
		const TTurnRun r = runTurning("object_model = " + std::string(model) + "\n" + common);
		std::cout << model << ": linked " << r.linked << ", merged " << r.merged << " at step "
		          << r.merge_step << ", merged features' RMSE " << r.feat_rmse << " m (" << r.feat_n
		          << " readings)\n";
		EXPECT_EQ(r.linked, 1u);
		EXPECT_EQ(r.merged, 1u);
		EXPECT_GT(r.feat_n, 0u);
		// Measured (2026-11-25): cv 0.0104 m, ctrv 0.0092 m (112 readings). The sighting with
		// the centroid of all features instead of the founders': cv 0.107 m (ctrv 0.011 m).
		EXPECT_LT(r.feat_rmse, 0.03) << "merged features off their true world positions";
	}
}
