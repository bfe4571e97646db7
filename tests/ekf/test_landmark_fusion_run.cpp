/** Landmark fusion in the dynamic EKF on simulated runs with track breaks (issue 29 item 1):
 *  - at the first fusion of a run, the filter's state equals a dense Kalman update on the
 *    difference with the full joint covariance of the run without fusion, rows and columns of
 *    the fused landmark deleted (1e-9); before it, the two runs are bit-identical;
 *  - the highway with track breaks, missed detections and clutter (pruning on in both runs):
 *    final map within 1.2 x the true landmarks seen, no pair fused wrongly (both IDs of every
 *    fused pair belong to one true landmark, by the simulator's class ground truth), on 10
 *    noise seeds; the mean ego ATE within 10 % of that of the runs without fusion. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/clutter_runs.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <map>
#include <set>

using namespace dynslam;

namespace
{
std::string filterIni(const std::string& extra)
{
	return dynslam_test::highwayFilterIni("prune_min_sightings = 3\nprune_window = 5\n" + extra);
}
const std::string kFuse = "fuse_landmarks_prob = 0.99\n";

/** The highway of config/highway_clutter.ini (10 % missed detections, 2 clutter readings per
 * step) with track breaks: a new ID with probability 0.05 per reading and after 4 unseen steps. */
sim::TScenarioOptions breaksScenario(uint32_t noiseSeed)
{
	sim::TScenarioOptions o =
	    sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/highway_clutter.ini");
	o.noise_seed = noiseSeed;
	o.effects.track_break_probability = 0.05;
	o.effects.track_break_gap = 4;
	return o;
}

void loadFilter(CDynamicKFSLAM2D& ekf, const std::string& extra)
{
	mrpt::config::CConfigFileMemory ini(filterIni(extra));
	ekf.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	ekf.loadOptions(ini, "DynamicKFSLAM");
}

/** Storage index of static landmark `id` in `layout`. */
std::vector<int> indicesOf(const estimator::CPaddedLayout& layout, int32_t id)
{
	for (size_t b = 0; b < layout.size(); ++b)
		if (layout[b].kind == estimator::BlockKind::StaticLandmark && layout[b].id == id)
			return layout.indices(b);
	throw std::logic_error("no landmark " + std::to_string(id));
}

struct TRun
{
	double ate = 0, ms = 0;
	size_t fused = 0, duplicates = 0;
	std::set<int32_t> live;
	std::vector<estimator::TFusionPair> fusions;
};

TRun run(const sim::TSimulatedRun& s, const io::TGroundTruth& gt, const std::string& extra)
{
	CDynamicKFSLAM2D ekf;
	loadFilter(ekf, extra);
	TRun r;
	r.ate = dynslam_test::runSteps(ekf, s, gt,
	                               [&](size_t, double ms)
	                               {
		                               r.ms += ms;
		                               r.fused += ekf.getLastStepReport().fused_static;
		                               r.duplicates +=
		                                   ekf.getLastStepReport().skipped_fused_duplicate;
	                               });
	for (const auto& l : ekf.getStaticLandmarks()) r.live.insert(l.id);
	r.fusions = ekf.getFusedLandmarks();
	return r;
}
}  // namespace

TEST(LandmarkFusionRun, FirstFusionEqualsTheDenseUpdateOfTheRunWithout)
{
	const sim::TScenarioOptions o = breaksScenario(1);
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun s = sim::simulateMeasurements(gt, o, o.noise_seed);
	CDynamicKFSLAM2D off, on;
	loadFilter(off, "");
	loadFilter(on, kFuse);
	bool checked = false;
	for (size_t k = 0; k < s.actions.size() && !checked; ++k)
	{
		off.processActionObservation(s.actions[k], s.frames[k]);
		on.processActionObservation(s.actions[k], s.frames[k]);
		if (on.getLastStepReport().fused_static == 0)
		{
			// Nothing fused yet: the key changes nothing.
			ASSERT_EQ(on.fullMean().asEigen(), off.fullMean().asEigen()) << "step " << k;
			ASSERT_EQ(on.fullCov().asEigen(), off.fullCov().asEigen()) << "step " << k;
			continue;
		}
		// The dense reference on the run without fusion: one noise-free update per fused pair
		// (H = [.. I .. -I ..], full covariance, Joseph form), then the fused rows deleted.
		Eigen::VectorXd x = off.fullMean().asEigen();
		Eigen::MatrixXd P = off.fullCov().asEigen();
		const Eigen::Index n = x.size();
		std::set<int> gone;
		size_t pairs = 0;
		for (const auto& f : on.getFusedLandmarks())
		{
			ASSERT_EQ(f.step, int(k));
			const std::vector<int> a = indicesOf(off.getLayout(), f.keep),
			                       b = indicesOf(off.getLayout(), f.gone);
			Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
			for (int i = 0; i < 2; ++i) H(i, a[i]) = 1, H(i, b[i]) = -1;
			const Eigen::MatrixXd S = H * P * H.transpose();
			EXPECT_NEAR((H * x).dot(S.inverse() * (H * x)), f.d2, 1e-9 * (1 + f.d2));
			const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
			x = x - K * (H * x);
			const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(n, n) - K * H;
			P = IKH * P * IKH.transpose();
			gone.insert(b.begin(), b.end());
			++pairs;
		}
		EXPECT_EQ(pairs, on.getLastStepReport().fused_static);
		std::vector<int> keep;
		for (int i = 0; i < n; ++i)
			if (!gone.count(i)) keep.push_back(i);
		const Eigen::VectorXd xr = x(keep);
		const Eigen::MatrixXd Pr = P(keep, keep);
		ASSERT_EQ(on.fullMean().size(), xr.size());
		const double dx = (on.fullMean().asEigen() - xr).cwiseAbs().maxCoeff();
		const double dP = (on.fullCov().asEigen() - Pr).cwiseAbs().maxCoeff();
		std::cout << "first fusion at step " << k << ": " << pairs << " pair(s), state of " << n
		          << " -> " << xr.size() << "; max |x - dense| " << dx << ", max |P - dense| " << dP
		          << " (max |P| " << Pr.cwiseAbs().maxCoeff() << ")\n";
		EXPECT_LT(dx, 1e-9);
		EXPECT_LT(dP, 1e-9);
		checked = true;
	}
	EXPECT_TRUE(checked) << "no fusion in the run";
}

TEST(LandmarkFusionRun, HighwayWithTrackBreaksMapWithin1p2xNoWrongFusionSameAte)
{
	// The ego ATE of one 121-step run is a few cm and moves either way with any change of the
	// data used (measured per seed without / with fusion: 0.26 x .. 1.67 x): the 10 % bound is
	// asserted on the mean over the 10 noise seeds, the per-seed values are printed.
	double ateOff = 0, ateOn = 0;
	for (uint32_t seed = 1; seed <= 10; ++seed)
	{
		const sim::TScenarioOptions o = breaksScenario(seed);
		const io::TGroundTruth gt = sim::buildGroundTruth(o);
		const sim::TSimulatedRun s = sim::simulateMeasurements(gt, o, o.noise_seed);
		// The truth: rawlog ID -> true landmark (static readings); clutter IDs map to -1.
		std::map<int32_t, int32_t> trueOf;
		std::set<int32_t> trueSeen;
		size_t breaks = 0;
		for (const auto& c : s.classes)
		{
			if (c.cls == io::TrueClass::Moving) continue;
			const int32_t t = c.cls == io::TrueClass::Static ? c.true_id : -1;
			if (!trueOf.count(c.id)) breaks += t >= 0 && c.id != c.true_id;
			trueOf[c.id] = t;
			if (t >= 0) trueSeen.insert(t);
		}
		const TRun off = run(s, gt, ""), on = run(s, gt, kFuse);
		size_t wrong = 0;
		for (const auto& f : on.fusions)
		{
			const int32_t a = trueOf.at(f.keep), b = trueOf.at(f.gone);
			if (a < 0 || a != b) ++wrong;
			EXPECT_TRUE(a >= 0 && a == b)
			    << "seed " << seed << ": " << f.gone << " (true " << b << ") fused into " << f.keep
			    << " (true " << a << ") at step " << f.step;
		}
		const double truth = double(trueSeen.size());
		std::cout << "seed " << seed << ": true landmarks seen " << trueSeen.size()
		          << ", static IDs after breaks " << breaks << "; final map without fusion "
		          << off.live.size() << " (" << double(off.live.size()) / truth << " x), with "
		          << on.live.size() << " (" << double(on.live.size()) / truth << " x); fused "
		          << on.fused << " (wrong " << wrong << ", duplicate readings skipped "
		          << on.duplicates << "); ATE " << off.ate << " -> " << on.ate << " m; ms "
		          << off.ms << " -> " << on.ms << "\n";
		EXPECT_EQ(on.fusions.size(), on.fused);
		EXPECT_GT(on.fused, 0u);
		EXPECT_GT(double(off.live.size()), 1.2 * truth) << "the breaks must matter here";
		EXPECT_LE(double(on.live.size()), 1.2 * truth) << "seed " << seed;
		ateOff += off.ate / 10;
		ateOn += on.ate / 10;
	}
	std::cout << "mean ego ATE over the seeds: without fusion " << ateOff << " m, with " << ateOn
	          << " m (" << ateOn / ateOff << " x)\n";
	EXPECT_LE(ateOn, 1.1 * ateOff);
}

TEST(LandmarkFusionRun, WithoutTrackBreaksNothingIsFusedAndTheRunIsUnchanged)
{
	// The shipped highway (no re-identified landmark): with the key on, no pair passes the rule,
	// and the estimate is that of the run without it, bit for bit.
	for (const char* cfg : {"/highway.ini", "/highway_clutter.ini"})
	{
		const sim::TScenarioOptions o = sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + cfg);
		const io::TGroundTruth gt = sim::buildGroundTruth(o);
		const sim::TSimulatedRun s = sim::simulateMeasurements(gt, o, o.noise_seed);
		const TRun off = run(s, gt, ""), on = run(s, gt, kFuse);
		EXPECT_EQ(on.fused, 0u) << cfg;
		EXPECT_EQ(on.live, off.live) << cfg;
		EXPECT_EQ(on.ate, off.ate) << cfg;
	}
}

TEST(LandmarkFusionRun, AFusedIdReadLaterUpdatesTheLandmarkItWasFusedInto)
{
	// After a fusion, the gone ID is an alias of the kept landmark (the step's AfterRoute hook of
	// the module landmark_fusion): a later reading of it updates the kept landmark, so the gone
	// ID never comes back into the map and is never fused a second time.
	size_t aliasReadings = 0;
	for (uint32_t seed = 1; seed <= 3; ++seed)
	{
		const sim::TScenarioOptions o = breaksScenario(seed);
		const io::TGroundTruth gt = sim::buildGroundTruth(o);
		const sim::TSimulatedRun s = sim::simulateMeasurements(gt, o, o.noise_seed);
		CDynamicKFSLAM2D ekf;
		loadFilter(ekf, kFuse);
		std::set<int32_t> gone;
		for (size_t k = 0; k < s.actions.size(); ++k)
		{
			const auto obs =
			    s.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
			for (const auto& m : obs->sensedData) aliasReadings += gone.count(m.landmarkID);
			ekf.processActionObservation(s.actions[k], s.frames[k]);
			for (const auto& f : ekf.getFusedLandmarks())
			{
				if (f.step != int(k)) continue;
				EXPECT_TRUE(gone.insert(f.gone).second)
				    << "seed " << seed << ": " << f.gone << " fused twice, step " << k;
			}
			for (const auto& l : ekf.getStaticLandmarks())
				EXPECT_EQ(gone.count(l.id), 0u)
				    << "seed " << seed << ": fused ID " << l.id << " back in the map, step " << k;
		}
	}
	std::cout << "readings of fused IDs after their fusion: " << aliasReadings << "\n";
	EXPECT_GT(aliasReadings, 0u) << "the test needs fused IDs read again";
}
