/** Pruning on the simulated highway with clutter (config/highway_clutter.ini: 2 clutter
 * readings per step with fresh IDs, 10 % missed detections; issue 29, item 2), the dynamic EKF
 * with prune_min_sightings = 3, prune_window = 5 against the same run without pruning:
 *  - the rule, counted against the truth (B_gt_classes): every ID read fewer than k times in
 *    the first N steps after its first reading, with its window closed before the end, was
 *    pruned; no true landmark read at least k times there was;
 *  - the final map holds at most 1.2 x the true landmarks seen; the ego ATE is within 10 % of
 *    the run without pruning;
 *  - record_dropped = false forgets what is pruned; the compressed EKF prunes the same
 *    landmarks (its passive landmarks are brought back when due) with the same estimate. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/clutter_runs.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <map>
#include <set>

using namespace dynslam;

namespace
{
constexpr int kMin = 3, kWindow = 5;

std::string pruneKeys()
{
	return "prune_min_sightings = " + std::to_string(kMin) +
	       "\nprune_window = " + std::to_string(kWindow) + "\n";
}

struct TRun
{
	double ate = 0, ms = 0;
	size_t pruned = 0, maxLive = 0;
	std::set<int32_t> live, recorded;
	std::vector<Eigen::Vector3d> ego;
};

TRun run(const sim::TSimulatedRun& s, const io::TGroundTruth& gt, const std::string& extra)
{
	mrpt::config::CConfigFileMemory ini(dynslam_test::highwayFilterIni(extra));
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(ini, "DynamicKFSLAM");
	TRun r;
	r.ate = dynslam_test::runSteps(ekf, s, gt,
	                               [&](size_t, double ms)
	                               {
		                               r.ms += ms;
		                               r.pruned += ekf.getLastStepReport().pruned_static;
		                               r.maxLive = std::max(r.maxLive, ekf.staticLandmarkCount());
		                               const auto p = ekf.getEgoPose().mean;
		                               r.ego.emplace_back(p.x(), p.y(), p.phi());
	                               });
	for (const auto& l : ekf.getStaticLandmarks()) r.live.insert(l.id);
	for (const auto& l : ekf.getDroppedStaticLandmarks()) r.recorded.insert(l.id);
	return r;
}

/** The truth: per static-range ID (landmarks and clutter; objects have their own range) the
 * step of its first reading and its readings in the window that starts there. */
struct TTruth
{
	std::map<int32_t, int> first, inWindow;
	std::set<int32_t> trueSeen;
	size_t clutterIds = 0;
};

TTruth truthOf(const sim::TSimulatedRun& s)
{
	TTruth t;
	for (const auto& c : s.classes)
	{
		if (c.cls == io::TrueClass::Moving) continue;
		if (!t.first.count(c.id))
		{
			t.first[c.id] = c.step;
			t.clutterIds += c.cls == io::TrueClass::Clutter;
		}
		if (c.step - t.first[c.id] < kWindow) ++t.inWindow[c.id];
		if (c.cls == io::TrueClass::Static) t.trueSeen.insert(c.id);
	}
	return t;
}
}  // namespace

TEST(PruneClutter, HighwayWithClutterMapWithin1p2xOfTheTruthSameAte)
{
	const sim::TScenarioOptions o =
	    sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/highway_clutter.ini");
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun s = sim::simulateMeasurements(gt, o, o.noise_seed);
	const int lastStep = int(s.actions.size()) - 1;

	const TTruth truth = truthOf(s);
	const auto& [first, inWindow, trueSeen, clutterIds] = truth;

	const TRun off = run(s, gt, "");
	const TRun on = run(s, gt, pruneKeys());
	const TRun forgot = run(s, gt, pruneKeys() + "record_dropped = false\n");
	const TRun compressed = run(s, gt,
	                            pruneKeys() +
	                                "static_update = compressed\ncompressed_passive_after = "
	                                "1\ncompressed_batch = 1\n");

	size_t due = 0, trueKept = 0, truePruned = 0;
	for (const auto& [id, f] : first)
	{
		const bool closed = f + kWindow - 1 <= lastStep;
		const bool fewer = inWindow.at(id) < kMin;
		const bool isTrue = trueSeen.count(id) != 0;
		if (closed && fewer)
		{
			++due;
			EXPECT_TRUE(on.recorded.count(id)) << "ID " << id << " read " << inWindow.at(id)
			                                   << " times from step " << f << ": not pruned";
			truePruned += isTrue;
		}
		else
		{
			EXPECT_TRUE(on.live.count(id)) << "ID " << id << " read " << inWindow.at(id)
			                               << " times from step " << f << ": pruned";
			EXPECT_FALSE(on.recorded.count(id)) << "ID " << id;
			trueKept += isTrue;
		}
	}
	EXPECT_EQ(off.pruned, 0u);
	EXPECT_EQ(off.live.size(), first.size());  // without pruning every ID is a landmark
	EXPECT_GE(on.pruned, due);                 // (IDs read again after pruning: pruned again)
	const double ratio = double(on.live.size()) / double(trueSeen.size());
	size_t trueLive = 0;
	for (const int32_t id : on.live) trueLive += trueSeen.count(id);
	std::cout << "highway_clutter (" << s.actions.size() << " steps): true landmarks seen "
	          << trueSeen.size() << ", clutter IDs " << clutterIds << "; final map without pruning "
	          << off.live.size() << ", with " << on.live.size() << " (" << ratio
	          << " x the truth; pruned " << on.pruned << " times, " << due
	          << " IDs due by the truth, of them true landmarks " << truePruned << ", kept "
	          << trueKept << "; true landmarks in the final map " << trueLive << "); largest map "
	          << off.maxLive << " vs " << on.maxLive << "; ego ATE " << off.ate << " m vs "
	          << on.ate << " m; ms in the steps " << off.ms << " vs " << on.ms << "\n";
	EXPECT_LE(ratio, 1.2);
	EXPECT_LE(on.ate, 1.1 * off.ate);
	EXPECT_GE(on.ate, 0.9 * off.ate);
	// record_dropped = false: the same run, nothing recorded.
	EXPECT_TRUE(forgot.recorded.empty());
	EXPECT_EQ(forgot.live, on.live);
	EXPECT_EQ(forgot.ate, on.ate);
	// Compressed: the same landmarks pruned, the same estimate (to rounding).
	EXPECT_EQ(compressed.live, on.live);
	EXPECT_EQ(compressed.recorded, on.recorded);
	EXPECT_EQ(compressed.pruned, on.pruned);
	for (size_t k = 0; k < on.ego.size(); ++k)
		EXPECT_LT((compressed.ego[k] - on.ego[k]).norm(), 1e-9) << "step " << k;
}
