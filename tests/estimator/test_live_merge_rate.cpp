/** The false-merge and missed-merge rates of classify_merge_live, measured by a seeded Monte Carlo
 * of whole filter runs (doc/results/classification.md "Merging two live objects", "Measured
 * rates"): the nominal alpha is not the false-merge rate (the cross-time covariance is not
 * tracked), so the rates are measured here over N seeded draws (world and noise seed) of a 60-step
 * highway:
 *
 * - Agent 1 alone in lane 1, its features 2 and 3 first seen at step 6 (a car split into two
 *   objects: one body, a merge is wanted; missed = no merge of its halves by the end);
 * - Agents 2 and 3, two bodies that are hard to tell apart: side by side 3.5 m apart with speed
 *   differences 0.1, 0.3 and 1 m/s, or Agent 3 passing Agent 2 (19 against 17.5 m/s, from 20 m
 *   behind), or at the same speed with every car driven by a white acceleration (object_accel_psd
 *   [q q 0], q = 0.01 and 0.001 m^2/s^3: a relative random walk, not a steady drift); a merge of
 *   them (or of any two true objects) is a false merge. With no speed
 *   difference the pair is one rigid body by motion alone (merged, as grouping would; reported,
 *   not a false merge of the test).
 *
 * The bounds are a few times the measured counts (binomial: count + 3 sd + 2), never tuned to
 * pass: a change that makes the test merge more easily fails. LMR_SEEDS overrides N (by hand). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "live_merge_setup.h"

using namespace dynslam;
using namespace dynslam::estimator;
using dynslam_test::delayHalfOfObject;

namespace
{
/** kTwoLanes of test_live_merge.cpp with Agent 3's start, speed and the seeds as parameters. */
std::string twoLanes(double x3, double v3, double psd, int seed)
{
	std::ostringstream s;
	s << "[Scenario]\ntype = highway\nname = live_merge_rate\ndt = 0.5\nsteps = 60\n"
	  << "world_seed = " << seed << "\nnoise_seed = " << seed << "\nstart_time = 1600000000\n"
	  << "[Sensor]\nrange = 55\nlabel = RB\nnoise_model = cartesian\ntypical_range = 27.5\n"
	  << "[Noise]\nlevel = w2v2\nobject_accel_psd = [" << psd << " " << psd << " 0]\n"
	  << "[Highway]\nlength = 1000\nnum_lanes = 4\nlane_width = 3.5\nego_lane = 0\n"
	  << "num_landmarks = 80\nlandmark_offset_min = 3\nlandmark_offset_max = 30\nnum_agents = 3\n"
	  << "[Ego]\nspeed = 17\nlength = 4.5\nwidth = 1.8\n";
	const double x0[3] = {12, 20, x3}, v[3] = {16, 17.5, v3};
	for (int a = 0; a < 3; ++a)
		s << "[Agent" << a + 1 << "]\ntype = car\nx0 = " << x0[a] << "\nlane0 = " << a + 1
		  << "\nspeed = " << v[a] << "\nlength = 4.5\nwidth = 1.8\nnum_features = 4\n";
	return s.str();
}

struct TOutcome
{
	int wrong = 0;       ///< merges of two different true objects
	int rightStep = -1;  ///< step of the first merge of two halves of one true object
};

/** One filter run; merges classified by the majority true object of each side. */
TOutcome runOnce(const std::string& scenario, const std::string& keys)
{
	const sim::TScenarioOptions o = sim::loadScenarioFromText(scenario);
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	sim::TSimulatedRun sim = sim::simulateMeasurements(gt, o, o.noise_seed);
	delayHalfOfObject(sim, gt.objects.front().object, 6);
	mrpt::config::CConfigFileMemory cfg(dynslam_test::highwayFilterIni(
	    "feature_labels = classify\n" + keys + "[Classify]\nclassify_merge_live = true\n"));
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	const auto& reg = ekf.router().registry();
	std::map<int32_t, std::map<int32_t, int>> votes;  // track -> true object -> readings
	const auto truthOf = [&](const TObjectEntry& e)
	{
		std::map<int32_t, int> v;
		for (const int32_t t : e.feature_ids)
			for (const auto& [truth, n] : votes[t]) v[truth] += n;
		int32_t best = -2, most = 0;
		for (const auto& [truth, n] : v)
			if (n > most) best = truth, most = n;
		return best;
	};
	TOutcome r;
	size_t row = 0;
	for (size_t k = 0; k < sim.actions.size(); ++k)
	{
		std::map<int32_t, std::pair<int32_t, TObjectEntry>> before;  // object -> (truth, entry)
		for (const auto& [id, e] : reg.objects()) before[id] = {truthOf(e), e};
		ekf.processActionObservation(sim.actions[k], sim.frames[k]);
		for (const auto& m : ekf.lastRoutedStep().readings)
		{
			const io::TReadingClass& c = sim.classes.at(row++);
			const bool moving = !m.candidate && m.route != Route::StaticKnown &&
			                    m.route != Route::StaticNew && m.object >= 0;
			if (moving) ++votes[m.reading.id][c.object];
		}
		if (ekf.getLastStepReport().objects_merged_live == 0) continue;
		for (const auto& [id, te] : before)  // a merged object left; who holds its first track
		{
			if (reg.has(id) || te.second.feature_ids.empty()) continue;
			for (const auto& [into, e] : reg.objects())
			{
				if (e.indexOf(te.second.feature_ids[0]) < 0 || !before.count(into)) continue;
				if (before.at(into).first != te.first)
					++r.wrong;
				else if (r.rightStep < 0)
					r.rightStep = int(k);
			}
		}
	}
	return r;
}

struct TRate
{
	int runs = 0, falseRuns = 0, missed = 0;
	std::vector<int> steps;  ///< steps from the late half's first sighting to its merge
	double medianSteps() const
	{
		if (steps.empty()) return -1;
		std::vector<int> s = steps;
		std::nth_element(s.begin(), s.begin() + long(s.size() / 2), s.end());
		return s[s.size() / 2];
	}
};

struct TCase
{
	const char* name;
	double x3, v3;   ///< Agent 3's start and speed (Agent 2: 20 m, 17.5 m/s)
	double psd = 0;  ///< every car's white acceleration [m^2/s^3] (object_accel_psd)
};
const TCase kCases[] = {{"side by side dv 0", 20, 17.5},
                        {"side by side dv 0.1", 20, 17.6},
                        {"side by side dv 0.3", 20, 17.8},
                        {"side by side dv 1", 20, 18.5},
                        {"passing", 0, 19},
                        {"same speed, accel psd 0.01", 20, 17.5, 0.01},
                        {"same speed, accel psd 0.001", 20, 17.5, 0.001}};

const std::string kCv =
    "object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_accel_psd = [0.1 0.1 1e-3]\n"
    "cv_velocity_prior_std = [0.5 0.5 0.05]\n";
const std::string kPaper = "[Classify]\nclassify_join = false\n";

int seeds(int n)
{
	const char* s = std::getenv("LMR_SEEDS");
	return s ? std::atoi(s) : n;
}

/** The rates of one model over the cases, N seeds each (the detector's alpha 1e-3). */
std::map<std::string, TRate> measure(const std::string& model, int n)
{
	std::map<std::string, TRate> out;
	for (const TCase& c : kCases)
	{
		TRate& r = out[c.name];
		for (int seed = 1; seed <= n; ++seed)
		{
			const TOutcome o = runOnce(twoLanes(c.x3, c.v3, c.psd, seed), model);
			++r.runs;
			r.falseRuns += o.wrong > 0;
			if (o.rightStep < 0)
				++r.missed;
			else
				r.steps.push_back(o.rightStep - 6);
		}
		std::cout << (model == kCv ? "cv" : "paper") << ", " << c.name << ": false merges "
		          << r.falseRuns << "/" << r.runs << ", split car missed " << r.missed << "/"
		          << r.runs << ", median steps to merge " << r.medianSteps() << "\n";
	}
	return out;
}

/** A few times the measured count: count + 3 binomial sd + 2. */
int bound(int count, int n)
{
	const double p = double(count) / n;
	return int(std::ceil(count + 3 * std::sqrt(n * p * (1 - p)) + 2));
}
}  // namespace

namespace
{
/** Measured 2026-11-25 over seeds 1..kSeeds (world and noise seed) of each case. */
constexpr int kSeeds = 40;
struct TExpect
{
	const std::string* model;
	int falseRuns[7];  ///< runs with a false merge, per case of kCases
	int missed;        ///< split-car halves never merged, over the 7 cases
	int medianSteps;   ///< steps from the late half's first sighting to its merge
};
// The detector's alpha 1e-3 (alpha 0.1 and 1e-6 gave counts within 6 of 100 of these: doc;
// classify_merge_live_alpha was removed on 2026-11-28 for that reason).
const TExpect kExpect[] = {{&kCv, {38, 0, 0, 0, 0, 1, 6}, 0, 7},
                           {&kPaper, {38, 2, 0, 0, 0, 5, 22}, 0, 22}};
}  // namespace

TEST(LiveMergeRate, FalseAndMissedMergesOverSeeds)
{
	const int n = seeds(kSeeds);
	for (const TExpect& e : kExpect)
	{
		SCOPED_TRACE(e.model == &kCv ? "cv" : "paper");
		const auto rates = measure(*e.model, n);
		int missed = 0, runs = 0;
		std::vector<int> steps;
		for (const auto& [name, r] : rates)
		{
			missed += r.missed, runs += r.runs;
			steps.insert(steps.end(), r.steps.begin(), r.steps.end());
		}
		if (n != kSeeds) continue;      // measuring by hand
		for (size_t c = 1; c < 7; ++c)  // two bodies: a merge is false
			EXPECT_LE(rates.at(kCases[c].name).falseRuns, bound(e.falseRuns[c], n))
			    << kCases[c].name;
		// The same speed side by side: one rigid body by motion alone (merged as measured).
		EXPECT_GE(rates.at(kCases[0].name).falseRuns,
		          2 * e.falseRuns[0] - bound(e.falseRuns[0], n));
		EXPECT_LE(missed, bound(e.missed, runs)) << "split car halves not merged";
		TRate all;
		all.steps = steps;
		EXPECT_LE(all.medianSteps(), 2 * e.medianSteps) << "steps from the split to the merge";
	}
}
