/** feature_labels = classify end to end on the simulated highway (doc/results/classification.md):
 * anonymous IDs (config/highway_anonymous.ini) against the ID-labelled filter on the same
 * noise, a parked car that drives off (config/highway_parked_driveoff.ini), and missed
 * detections with clutter (config/highway_clutter.ini). Thresholds are a few times the
 * measured values (measured values in the comments and in doc/results/classification.md). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

using namespace dynslam;

namespace
{
const std::string kIni = dynslam_test::highwayFilterIni();

sim::TScenarioOptions scenario(const std::string& cfg)
{
	return dynslam_test::shippedScenario(cfg);
}

struct TResult
{
	double ate = 0, maxErr = 0;
	eval::TBinaryScores reading, track;
	eval::TDelaySummary delays;
	double ari = 0;
	size_t objects = 0, reclassified = 0, converted = 0, stopped = 0, unknownIds = 0, held = 0,
	       candidates = 0, updates = 0;
	size_t restarted = 0, split = 0, joined = 0, joinedF0 = 0;  ///< doc/results/classification.md
	/** Largest error [m] of the f_0 estimates of late joiners and of founders: against the true
	 * position of the track's (majority) true feature at its object's time 0. */
	double joinerF0Err = 0, founderF0Err = 0;
};

/** Fills r.joinerF0Err and r.founderF0Err (classify runs; written track IDs only). */
void f0Errors(const CDynamicKFSLAM2D& ekf, const io::TGroundTruth& gt,
              const std::vector<io::TReadingClass>& classes, TResult& r)
{
	const auto tracks = ekf.getObjectTracks();
	for (const auto& f : ekf.getObjectFeatures())
	{
		if (!f.at_time0) continue;
		const auto c = std::find_if(classes.begin(), classes.end(),
		                            [&](const io::TReadingClass& rc)
		                            { return rc.id == f.id && rc.object >= 0; });
		const auto o = std::find_if(gt.objects.begin(), gt.objects.end(),
		                            [&](const auto& g)
		                            { return c != classes.end() && g.object == c->object; });
		if (o == gt.objects.end()) continue;
		const int t0 = tracks.at(f.object).first_step;
		const double e = (f.mean - o->features[size_t(t0)].col(c->feature)).norm();
		double& worst = f.step == t0 ? r.founderF0Err : r.joinerF0Err;
		worst = std::max(worst, e);
	}
}

/** The labelled filter that knows every motion onset and stop: the readings of an object
 * while it stands still (true class static) get a static landmark ID (90000 + 100 object +
 * feature), the others keep their labelled ID, so the object starts at its first moving
 * reading (its time 0) and its parked readings were static landmarks. */
void relabelWithOnsets(sim::TSimulatedRun& sim)
{
	for (const io::TReadingClass& c : sim.classes)
	{
		if (c.cls != io::TrueClass::Static || c.object < 0) continue;
		auto obs = sim.frames.at(size_t(c.step))
		               ->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		auto& d = obs->sensedData.at(size_t(c.index));
		ASSERT_EQ(d.landmarkID, c.true_id) << "a labelled run";
		d.landmarkID = 90000 + 100 * c.object + c.feature;
	}
}

/** Runs the EKF on the scenario; classify: feature_labels = classify (extra: more keys);
 * knowsOnsets: a labelled run with relabelWithOnsets. */
TResult run(const sim::TScenarioOptions& o, bool classify, const std::string& extra = "",
            const std::string& sigmaV = "1e-5", bool knowsOnsets = false,
            const std::string& common = "")
{
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	sim::TSimulatedRun sim = sim::simulateMeasurements(gt, o, o.noise_seed);
	if (knowsOnsets) relabelWithOnsets(sim);
	std::string ini = kIni;
	ini.replace(ini.find("1e-5 1e-5"), 9, sigmaV + " " + sigmaV);
	ini.insert(ini.find("[DynamicKFSLAM_"), common);
	if (classify)  // after `common`, which may end in a module's section
		ini.insert(ini.find("[DynamicKFSLAM_"),
		           "[DynamicKFSLAM]\nfeature_labels = classify\n" + extra);
	mrpt::config::CConfigFileMemory cfg(ini);
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	TResult r;
	std::vector<eval::Decision> dec;
	std::vector<int64_t> group;
	double se = 0;
	for (size_t k = 0; k < sim.actions.size(); ++k)
	{
		ekf.processActionObservation(sim.actions[k], sim.frames[k]);
		for (const auto& m : ekf.lastRoutedStep().readings)
		{
			using estimator::Route;
			const bool st = m.route == Route::StaticKnown || m.route == Route::StaticNew;
			dec.push_back(m.candidate     ? eval::Decision::Undecided
			              : st            ? eval::Decision::Static
			              : m.object >= 0 ? eval::Decision::Moving
			                              : eval::Decision::Undecided);
			group.push_back(m.object);
		}
		r.reclassified += ekf.getLastStepReport().reclassified_static;
		r.converted += ekf.getLastStepReport().converted_static;
		r.stopped += ekf.getLastStepReport().classify_stopped;
		r.unknownIds += ekf.getLastStepReport().skipped_unknown_id;
		r.held += ekf.getLastStepReport().classify_held;
		r.candidates += ekf.getLastStepReport().classify_candidates;
		r.updates += ekf.getLastStepReport().static_updates;
		r.restarted += ekf.getLastStepReport().classify_restarted;
		r.split += ekf.getLastStepReport().classify_split;
		r.joined += ekf.getLastStepReport().classify_joined;
		r.joinedF0 += ekf.getLastStepReport().object_features_joined;
		const auto e = ekf.getEgoPose().mean;
		const double d2 = std::pow(e.x() - gt.ego[k][0], 2) + std::pow(e.y() - gt.ego[k][1], 2);
		se += d2;
		r.maxErr = std::max(r.maxErr, std::sqrt(d2));
	}
	r.ate = std::sqrt(se / double(sim.actions.size()));
	EXPECT_EQ(dec.size(), sim.classes.size()) << "one decision per reading";
	if (dec.size() != sim.classes.size()) return r;
	r.reading = eval::perReadingScores(sim.classes, dec);
	r.track = eval::perTrackScores(sim.classes, dec);
	r.delays = eval::detectionDelays(sim.classes, dec);
	r.ari = eval::groupingAri(sim.classes, group);
	r.objects = ekf.getObjectTracks().size();
	if (classify) f0Errors(ekf, gt, sim.classes, r);
	return r;
}

void print(const std::string& what, const TResult& r)
{
	std::cout << what << ": ATE " << r.ate << " m (max " << r.maxErr << "), reading P/R/F1 "
	          << r.reading.precision << "/" << r.reading.recall << "/" << r.reading.f1
	          << ", track F1 " << r.track.f1 << ", ARI " << r.ari << ", objects " << r.objects
	          << ", reclassified " << r.reclassified << ", converted " << r.converted
	          << ", stopped " << r.stopped << ", held " << r.held << ", candidates " << r.candidates
	          << ", static updates " << r.updates << ", onsets detected " << r.delays.detected
	          << "/" << r.delays.onsets.size() << " max delay " << r.delays.max_delay
	          << ", restarted " << r.restarted << ", split " << r.split << ", joined " << r.joined
	          << " (f_0 " << r.joinedF0 << ", error " << r.joinerF0Err << " m; founders "
	          << r.founderF0Err << " m)\n";
}
}  // namespace

TEST(ClassifyHighway, AnonymousIdsAreClassifiedAndTheEgoStaysClose)
{
	const TResult labelled = run(scenario("highway.ini"), false);
	const TResult cls = run(scenario("highway_anonymous.ini"), true);
	print("labelled", labelled);
	print("classify", cls);
	// Measured: track F1 1, reading F1 0.984 (the first reading of each track is undecided),
	// ATE 0.1274 m vs 0.1276 m labelled (on highway.ini, without the track breaks).
	EXPECT_GE(cls.track.f1, 0.95);
	EXPECT_GE(cls.reading.f1, 0.95);
	EXPECT_LE(cls.ate, 1.1 * labelled.ate + 0.01);
}

/** The anonymous highway at another noise level, with (anonymous) or without anonymous IDs. */
sim::TScenarioOptions anonymousAt(const std::string& level, bool anonymous)
{
	std::ifstream f(std::string(DYNSLAM_CONFIG_DIR) + "/highway_anonymous.ini");
	std::stringstream ss;
	ss << f.rdbuf();
	std::string s = ss.str();
	s.replace(s.find("level = w2v2"), 12, "level = " + level);
	s.replace(s.find("anonymous_ids   = true"), 22,
	          std::string("anonymous_ids = ") + (anonymous ? "true" : "false"));
	return sim::loadScenarioFromText(s);
}

TEST(ClassifyHighway, NoiseLevelsAgainstTheLabelledFilterOnTheSameTrackBreaks)
{
	for (const char* level :
	     {"w1v1", "w1v2", "w1v3", "w2v1", "w2v2", "w2v3", "w3v1", "w3v2", "w3v3"})
	{
		const std::string v = level[3] == '1' ? "1e-6" : level[3] == '2' ? "1e-5" : "1e-4";
		const TResult labelled = run(anonymousAt(level, false), false, "", v);
		const TResult cls = run(anonymousAt(level, true), true, "", v);
		print(std::string(level) + " labelled", labelled);
		print(std::string(level) + " classify", cls);
		// Measured: per-reading F1 0.983..0.985, per-track F1 0.973..1
		// (doc/results/classification.md).
		EXPECT_GE(cls.reading.f1, 0.95) << level;
		EXPECT_GE(cls.track.f1, 0.9) << level;
		// Measured: classify / labelled ATE 0.92 (w3v2) .. 1.012 (w3v1); issue 12's target.
		EXPECT_LE(cls.ate, 1.1 * labelled.ate + 0.01) << level;
	}
}

/** A parked car that drives off: surgery (default) and restart against the labelled filter that
 * knows the onset (relabelWithOnsets) and the one that has the car as an object throughout. */
struct TDriveOff
{
	TResult labelled, onsets, surgery, restart;
};
TDriveOff driveOff(const std::string& cfg, const std::string& common = "")
{
	TDriveOff d;
	const sim::TScenarioOptions o = scenario(cfg);
	d.labelled = run(o, false, "", "1e-5", false, common);
	d.onsets = run(o, false, "", "1e-5", true, common);
	d.surgery = run(o, true, "", "1e-5", false, common);
	d.restart = run(o, true, "[Classify]\nclassify_reclassify = restart\n", "1e-5", false, common);
	const std::string w = cfg + (common.empty() ? "" : " (" + common.substr(0, 15) + ")");
	print(w + " labelled", d.labelled);
	print(w + " labelled, knows the onset", d.onsets);
	print(w + " classify (surgery)", d.surgery);
	print(w + " classify (restart)", d.restart);
	for (const auto& o : d.surgery.delays.onsets)
		std::cout << "onset object " << o.object << " feature " << o.feature << " at "
		          << o.onset_step << " detected " << o.detect_step << "\n";
	return d;
}

TEST(ClassifyHighway, ParkedCarDrivingOffIsReclassified)
{
	// Agent 4 in view ~3 steps before its onset (step 40).
	const TDriveOff d = driveOff("highway_parked_driveoff.ini");
	// Measured: the 4 features of the car that drives off reclassified 2 steps after the onset
	// (reclassify_count = 3 readings beyond the gate).
	EXPECT_EQ(d.surgery.converted, 4u);
	EXPECT_EQ(d.surgery.reclassified, 0u);
	EXPECT_EQ(d.restart.reclassified, 4u);
	EXPECT_EQ(d.restart.converted, 0u);
	for (const TResult* r : {&d.surgery, &d.restart})
	{
		EXPECT_EQ(r->delays.detected, r->delays.onsets.size());
		EXPECT_GE(r->delays.onsets.size(), 4u);
		EXPECT_LE(r->delays.max_delay, 6);
		EXPECT_LE(r->ate, 1.2 * d.onsets.ate);
		EXPECT_LE(r->ate, 1.2 * d.labelled.ate);
	}
}

TEST(ClassifyHighway, ParkedCarInViewDrivingOffSurgeryAgainstRestart)
{
	// Agent 4 in view ~12 steps while parked, then drives off at step 40 (issue 12's target:
	// reclassified within 10 steps, ego ATE within 20 % of the filter that knows the onset).
	const TDriveOff d = driveOff("highway_driveoff_in_view.ini");
	EXPECT_EQ(d.surgery.converted, 4u);
	EXPECT_EQ(d.restart.reclassified, 4u);
	for (const TResult* r : {&d.surgery, &d.restart})
	{
		EXPECT_EQ(r->delays.detected, r->delays.onsets.size());
		EXPECT_GE(r->delays.onsets.size(), 4u);
		EXPECT_LE(r->delays.max_delay, 10);
		EXPECT_LE(r->ate, 1.2 * d.onsets.ate);
	}
}

// classify_static_test = map (the EKF's own innovation of a static reading, chosen on MRCLAM):
// on the simulated highway the same decisions as the robot-frame test. Measured 2026-11-24:
// the anonymous highway's track F1, reading F1 and ATE equal to the robot-frame run's; the car
// that drives off converted at the same step.
TEST(ClassifyHighway, MapStaticTestKeepsTheHighwayDecisions)
{
	const std::string map = "[Classify]\nclassify_static_test = map\n";
	const TResult robot = run(scenario("highway_anonymous.ini"), true);
	const TResult cls = run(scenario("highway_anonymous.ini"), true, map);
	print("classify, static test map", cls);
	EXPECT_GE(cls.track.f1, 0.95);
	EXPECT_GE(cls.reading.f1, 0.95);
	EXPECT_LE(cls.ate, 1.1 * robot.ate + 0.01);
	const sim::TScenarioOptions o = scenario("highway_driveoff_in_view.ini");
	const TResult onsets = run(o, false, "", "1e-5", true);
	const TResult off = run(o, true, map);
	print("drive-off, static test map", off);
	EXPECT_EQ(off.converted, 4u);
	EXPECT_EQ(off.delays.detected, off.delays.onsets.size());
	EXPECT_LE(off.delays.max_delay, 10);
	EXPECT_LE(off.ate, 1.2 * onsets.ate);
}

TEST(ClassifyHighway, ParkedCarInViewDrivingOffWithConstantVelocityObjects)
{
	const TDriveOff d =
	    driveOff("highway_driveoff_in_view.ini",
	             "object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_accel_psd = [0.01 0.01 1e-4]\n"
	             "cv_velocity_prior_std = [0.5 0.5 0.05]\n");
	EXPECT_EQ(d.surgery.converted, 4u);
}

TEST(ClassifyHighway, StoppingCarBecomesStatic)
{
	// Agent 6 of highway_parked_driveoff.ini comes to rest at t = 34 s (step 68).
	const sim::TScenarioOptions o = scenario("highway_parked_driveoff.ini");
	const TResult onsets = run(o, false, "", "1e-5", true);
	const TResult off = run(o, true);
	print("stopping: labelled, knows the onset", onsets);
	print("stopping: classify, stop_count 0", off);
	std::map<int, TResult> on;
	for (const int n : {2, 3, 5})
	{
		on[n] = run(o, true, "[Classify]\nclassify_stop_count = " + std::to_string(n) + "\n");
		print("stopping: classify, stop_count " + std::to_string(n), on[n]);
	}
	// Measured: with 2 or 3 the 4 features of Agent 6 become static landmarks (8 / 4 more
	// static updates), reading F1 0.984 / 0.982 against 0.977, ATE 0.0628 / 0.0632 m against
	// 0.0631 m (the labelled filter that knows the stop: 0.0597 m); with 5 the ego has passed
	// the car before 5 consistent readings: nothing changes.
	EXPECT_EQ(off.stopped, 0u);
	for (const int n : {2, 3})
	{
		EXPECT_EQ(on[n].stopped, 4u) << n;
		EXPECT_GT(on[n].reading.f1, off.reading.f1) << n;
		EXPECT_LE(on[n].ate, 1.2 * onsets.ate) << n;
	}
	EXPECT_EQ(on[5].stopped, 0u);
}

TEST(ClassifyHighway, MissedDetectionsAndClutterDoNotDiverge)
{
	const TResult labelled = run(scenario("highway_clutter.ini"), false);
	const TResult cls = run(scenario("highway_clutter.ini"), true);
	print("labelled", labelled);
	print("classify", cls);
	// Measured: max ego error 0.230 m (labelled 0.230 m), reading F1 0.990, track F1 1.
	EXPECT_LT(cls.maxErr, 2 * labelled.maxErr);
	EXPECT_GE(cls.reading.f1, 0.95);
	EXPECT_GE(cls.track.f1, 0.95);
	// Late joining (track breaks after missed detections): measured 4 joiners, each given an
	// f_0; grouping ARI 0.97 (0.46 without joining).
	EXPECT_GE(cls.joined, 2u);
	EXPECT_EQ(cls.joinedF0, cls.joined);
	EXPECT_GE(cls.ari, 0.9);
	EXPECT_LT(cls.joinerF0Err, 3 * cls.founderF0Err + 0.05);
}

TEST(ClassifyHighway, BadOptionsAreClearErrors)
{
	const auto load = [](const std::string& extra)
	{
		std::string ini = kIni;
		ini.insert(ini.find("[DynamicKFSLAM_"), extra);
		mrpt::config::CConfigFileMemory cfg(ini);
		CDynamicKFSLAM2D ekf;
		ekf.loadOptions(cfg, "DynamicKFSLAM");
	};
	const auto expectError = [&](const std::string& extra, const std::string& key)
	{
		try
		{
			load(extra);
			ADD_FAILURE() << extra << " accepted";
		}
		catch (const std::exception& e)
		{
			EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
		}
	};
	expectError("feature_labels = anonymous\n", "feature_labels");
	expectError("feature_labels = classify\n[Classify]\nclassify_alpha = 1.5\n", "classify_alpha");
	expectError("feature_labels = classify\n[Classify]\nclassify_beta = 0\n", "classify_beta");
	expectError("feature_labels = classify\n[Classify]\nclassify_max_window = 1\n",
	            "classify_max_window");
	expectError("[Classify]\nclassify_typo = 1\n", "classify_typo");
	expectError("feature_labels = classify\n[Classify]\nclassify_static_test = world\n",
	            "classify_static_test");
	// Removed keys (the drift test, 2026-11-28) are unknown keys now: an error, never ignored.
	expectError("feature_labels = classify\n[Classify]\nclassify_drift_window = 40\n",
	            "classify_drift_window");
	EXPECT_NO_THROW(load("feature_labels = classify\n[Classify]\nclassify_alpha = 0.05\n"));
	// The default is the ID-range router, unchanged.
	mrpt::config::CConfigFileMemory cfg(kIni);
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	EXPECT_EQ(ekf.router().name(), "ids");
}
