/** Merging a linked object end to end (classify_merge_linked, doc/results/classification.md
 * "Merging a linked object"): config/highway_anonymous.ini with detection-group hints, whose two
 * cars come back under new IDs after a track break, through the classifying EKF with object_model =
 * cv. With the key on, each link merges the new object into the lost one (fewer objects, the lost
 * object's feature set grows by the new tracks); the merged objects' velocity and the world
 * positions of their features stay close to the truth; off is today's filter bit for bit; with
 * the paper's model the key changes nothing. */
#include <dynslam/core/models/object_motion.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "object_merge_setup.h"

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
using dynslam_test::featureWorld;

const char* kCv =
    "feature_labels = classify\n[Classify]\nclassify_use_hints = true\n[ObjectModel]\ncv_dt = 0.5\n"
    "cv_velocity_prior_std = [0.5 0.5 0.05]\n";

struct TMergeRun
{
	double ate = 0, ari = 0;
	size_t linked = 0, merged = 0, skipped = 0, objects = 0;
	std::vector<Eigen::VectorXd> x;  ///< the state after every step
	/** Per merged object: RMS over the steps after its merge of the speed error of its reference
	 * point and of the world position error of its features seen in the step. */
	double vel_rmse = 0, feat_rmse = 0;
	size_t vel_n = 0, feat_n = 0;
	double all_vel_rmse = 0;  ///< the same speed error over every object with a velocity
	size_t all_vel_n = 0;
	std::set<int32_t> into;  ///< the objects that took a merge
};

sim::TScenarioOptions anonymousWithHints()
{
	std::ifstream f(std::string(DYNSLAM_CONFIG_DIR) + "/highway_anonymous.ini");
	std::stringstream ss;
	ss << f.rdbuf();
	std::string s = ss.str();
	s.replace(s.find("[Effects]"), 9, "[Effects]\ndetection_groups = true");
	return sim::loadScenarioFromText(s);
}

/** Squared speed error of every object with a velocity at step k (0 < k < last): its reference
 * point (the founders' centroid moved by xi) against the central difference of the true
 * positions of its founders' features (truthOf: track -> true object and feature). */
std::map<int32_t, double> speedErrors(
    const CDynamicKFSLAM2D& ekf, const io::TGroundTruth& gt,
    const std::map<int32_t, const io::TObjectGroundTruth*>& trueObj,
    const std::map<int32_t, std::pair<int32_t, int32_t>>& truthOf, size_t k)
{
	std::map<int32_t, double> out;
	const auto& L = ekf.getLayout();
	for (size_t b = 0; b < L.size(); ++b)
	{
		if (L[b].kind != BlockKind::ObjectVelocity) continue;
		const estimator::TObjectEntry& e = ekf.router().registry().at(L[b].object);
		Eigen::Vector2d c0 = Eigen::Vector2d::Zero(), c1 = Eigen::Vector2d::Zero();
		int n = 0;
		for (int j = 0; j < e.founders; ++j)
		{
			const auto it = truthOf.find(e.feature_ids[size_t(j)]);
			if (it == truthOf.end() || it->second.first < 0) continue;
			const io::TObjectGroundTruth& obj = *trueObj.at(it->second.first);
			c0 += obj.features.at(k - 1).col(it->second.second);
			c1 += obj.features.at(k + 1).col(it->second.second);
			++n;
		}
		if (n == 0) continue;
		const Eigen::Vector2d vt = (c1 - c0) / n / (gt.t[k + 1] - gt.t[k - 1]);
		const std::vector<int> iv = L.indices(b);
		out[L[b].object] =
		    (Eigen::Vector2d(ekf.fullMean()[size_t(iv[0])], ekf.fullMean()[size_t(iv[1])]) - vt)
		        .squaredNorm();
	}
	return out;
}

TMergeRun runMerge(const std::string& keys)
{
	const sim::TScenarioOptions o = anonymousWithHints();
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun sim = sim::simulateMeasurements(gt, o, o.noise_seed);
	mrpt::config::CConfigFileMemory cfg(dynslam_test::highwayFilterIni(keys));
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	TMergeRun r;
	std::vector<int64_t> group;
	double se = 0, sv = 0, sf = 0, sa = 0;
	size_t row = 0;
	std::map<int32_t, std::pair<int32_t, int32_t>> truthOf;  // track -> (true object, feature)
	std::map<int32_t, const io::TObjectGroundTruth*> trueObj;
	for (const auto& t : gt.objects) trueObj[t.object] = &t;
	for (size_t k = 0; k < sim.actions.size(); ++k)
	{
		ekf.processActionObservation(sim.actions[k], sim.frames[k]);
		const TRoutedStep& st = ekf.lastRoutedStep();
		for (const auto& m : st.readings)
		{
			const io::TReadingClass& c = sim.classes.at(row++);
			if (m.reading.id >= 0) truthOf[m.reading.id] = {c.object, c.feature};
			const bool moving = !m.candidate && m.route != Route::StaticKnown &&
			                    m.route != Route::StaticNew && m.object >= 0;
			group.push_back(moving ? m.identity : -1);
		}
		r.linked += st.linked;
		r.merged += ekf.getLastStepReport().objects_merged;
		r.skipped += ekf.getLastStepReport().merges_skipped;
		for (const auto& mg : st.merges)
			if (ekf.router().registry().has(mg.into) && !ekf.router().registry().has(mg.from))
				r.into.insert(mg.into);
		// The merged objects after their merge: their features seen now, and the velocity of
		// the reference point (the founders' centroid moved by xi) against the truth's.
		for (const auto& m : st.readings)
			if (m.route == Route::ObjectTimeT && r.into.count(m.object) &&
			    truthOf.count(m.reading.id))
			{
				const auto [to, tf] = truthOf.at(m.reading.id);
				if (to < 0 || tf < 0) continue;
				const Eigen::Vector2d t = trueObj.at(to)->features.at(k).col(tf);
				const auto w = featureWorld(ekf, m.object, m.reading.id);
				if (!w) continue;
				sf += (*w - t).squaredNorm();
				++r.feat_n;
			}
		if (k > 0 && k + 1 < sim.actions.size())
			for (const auto& [obj, e2] : speedErrors(ekf, gt, trueObj, truthOf, k))
			{
				sa += e2;
				++r.all_vel_n;
				if (!r.into.count(obj)) continue;
				sv += e2;
				++r.vel_n;
			}
		const auto e = ekf.getEgoPose().mean;
		se += std::pow(e.x() - gt.ego[k][0], 2) + std::pow(e.y() - gt.ego[k][1], 2);
		r.x.push_back(ekf.fullMean().asEigen());
	}
	r.ate = std::sqrt(se / double(sim.actions.size()));
	r.ari = eval::groupingAri(sim.classes, group);
	r.objects = ekf.router().registry().objects().size();
	r.vel_rmse = r.vel_n ? std::sqrt(sv / double(r.vel_n)) : 0;
	r.feat_rmse = r.feat_n ? std::sqrt(sf / double(r.feat_n)) : 0;
	r.all_vel_rmse = r.all_vel_n ? std::sqrt(sa / double(r.all_vel_n)) : 0;
	return r;
}

void print(const char* what, const TMergeRun& r)
{
	std::cout << what << ": ATE " << r.ate << " m, ARI " << r.ari << ", objects " << r.objects
	          << ", linked " << r.linked << ", merged " << r.merged << ", skipped " << r.skipped
	          << ", merged objects' speed RMSE " << r.vel_rmse << " m/s (" << r.vel_n
	          << " steps), feature RMSE " << r.feat_rmse << " m (" << r.feat_n
	          << " readings); all objects' speed RMSE " << r.all_vel_rmse << " m/s (" << r.all_vel_n
	          << ")\n";
}
}  // namespace

TEST(ObjectMergeHighway, LinkedCarsMergeIntoTheirLostObjects)
{
	struct TSetting
	{
		const char* keys;
		bool accurate;  ///< the process noise covers the cars' speed changes in the gap
	};
	// A loose process noise (the cars change speed by up to 2.5 m/s in their gaps); the tight one
	// of config/compare_tunnel.ini with its gate (setting E without the anchor), which cannot
	// follow them (documented), and the same with the fallback of a lost object.
	const TSetting settings[] = {
	    {"object_model = cv\n[ObjectModel]\ncv_accel_psd = [0.1 0.1 1e-3]\n", true},
	    {"object_model = ctrv\n[ObjectModel]\ncv_accel_psd = [0.1 0.1 1e-3]\n", true},
	    {"object_model = cv\n[ObjectModel]\ncv_accel_psd = [1e-7 1e-7 1e-9]\ncv_gate = 0.999\n",
	     false},
	    {"object_model = cv\n[ObjectModel]\ncv_accel_psd = [1e-7 1e-7 1e-9]\ncv_gate = 0.999\n"
	     "cv_fallback_steps = 3\n",
	     false}};
	for (const TSetting& st : settings)
	{
		SCOPED_TRACE(st.keys);
		const std::string cv = std::string(kCv) + "[DynamicKFSLAM]\n" + st.keys;
		const TMergeRun off = runMerge(cv);
		const TMergeRun def = runMerge(cv + "[Classify]\nclassify_merge_linked = false\n");
		const TMergeRun on = runMerge(cv + "[Classify]\nclassify_merge_linked = true\n");
		std::cout << st.keys;
		print("merge off", off);
		print("merge on", on);
		ASSERT_EQ(def.x.size(), off.x.size());
		for (size_t k = 0; k < off.x.size(); ++k)
			ASSERT_EQ(def.x[k], off.x[k]) << "key off = today's filter bit for bit, step " << k;
		EXPECT_EQ(off.merged, 0u);
		EXPECT_EQ(on.linked, 2u);
		EXPECT_EQ(on.merged, 2u);
		EXPECT_EQ(on.objects + 2, off.objects) << "each merge removes the new object";
		EXPECT_EQ(on.ari, off.ari) << "identities are the links' in both";
		EXPECT_GT(on.feat_n, 0u);
		EXPECT_GT(on.vel_n, 0u);
		// Measured (2026-11-25): ATE 0.1275 -> 0.1274, 0.1137 -> 0.1138, 0.1192 -> 0.1195 m.
		EXPECT_LT(on.ate, 1.1 * off.ate + 0.01);
		if (!st.accurate) continue;
		// Measured: merged features 0.356 m from the truth, their object's speed 0.62 m/s off.
		EXPECT_LT(on.feat_rmse, 1.0);
		EXPECT_LT(on.vel_rmse, 1.9);
	}
}

TEST(ObjectMergeHighway, PaperModelIgnoresTheKey)
{
	// The paper's model has no prediction across a gap: the key is documented to change nothing.
	const std::string paper = "feature_labels = classify\n[Classify]\nclassify_use_hints = true\n";
	const TMergeRun off = runMerge(paper);
	const TMergeRun on = runMerge(paper + "[Classify]\nclassify_merge_linked = true\n");
	EXPECT_EQ(on.linked, 2u);
	EXPECT_EQ(on.merged + on.skipped, 0u);
	ASSERT_EQ(on.x.size(), off.x.size());
	for (size_t k = 0; k < off.x.size(); ++k) ASSERT_EQ(on.x[k], off.x[k]) << "step " << k;
	EXPECT_EQ(on.ari, off.ari);
}

TEST(ObjectMergeHighway, BadValueIsAnErrorAndTheKeyIsDumped)
{
	CDynamicKFSLAM2D ekf;
	mrpt::config::CConfigFileMemory bad(dynslam_test::highwayFilterIni(
	    "feature_labels = classify\n[Classify]\nclassify_merge_linked = maybe\n"));
	try
	{
		ekf.loadOptions(bad, "DynamicKFSLAM");
		ADD_FAILURE() << "[Classify]\nclassify_merge_linked = maybe accepted";
	}
	catch (const std::exception& e)
	{
		EXPECT_NE(std::string(e.what()).find("classify_merge_linked"), std::string::npos)
		    << e.what();
	}
	mrpt::config::CConfigFileMemory good(dynslam_test::highwayFilterIni(
	    "feature_labels = classify\n[Classify]\nclassify_merge_linked = true\n"));
	ekf.loadOptions(good, "DynamicKFSLAM");
	std::ostringstream d;
	ekf.options.dumpToTextStream(d);
	EXPECT_NE(d.str().find("classify_merge_linked          = true"), std::string::npos);
}
