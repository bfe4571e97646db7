/** feature_labels = classify end to end on the simulated highway (doc/classification.md):
 * anonymous IDs (config/highway_anonymous.ini) against the ID-labelled filter on the same
 * noise, a parked car that drives off (config/highway_parked_driveoff.ini), and missed
 * detections with clutter (config/highway_clutter.ini). Thresholds are a few times the
 * measured values (measured values in the comments and in doc/classification.md). */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <sstream>

using namespace dynslam;

namespace
{
const std::string kIni =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-5 1e-5]\n"
    "motion_noise = action\n"
    "Sigma_0 = [1e-5 1e-5 1e-7]\n"
    "Sigma_xi = [0.1 0.1]\n"
    "[DynamicKFSLAM_KalmanFilter]\n"
    "method = kfEKFNaive\n";

sim::TScenarioOptions scenario(const std::string& cfg)
{
	return sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/" + cfg);
}

struct TResult
{
	double ate = 0, maxErr = 0;
	eval::TBinaryScores reading, track;
	eval::TDelaySummary delays;
	double ari = 0;
	size_t objects = 0, reclassified = 0, unknownIds = 0;
};

/** Runs the EKF on the scenario; classify: feature_labels = classify (extra: more keys). */
TResult run(const sim::TScenarioOptions& o, bool classify, const std::string& extra = "")
{
	const TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun sim = sim::simulateMeasurements(gt, o, o.noise_seed);
	std::string ini = kIni;
	if (classify) ini.insert(ini.find("[DynamicKFSLAM_"), "feature_labels = classify\n" + extra);
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
			dec.push_back(st              ? eval::Decision::Static
			              : m.object >= 0 ? eval::Decision::Moving
			                              : eval::Decision::Undecided);
			group.push_back(m.object);
		}
		r.reclassified += ekf.getLastStepReport().reclassified_static;
		r.unknownIds += ekf.getLastStepReport().skipped_unknown_id;
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
	return r;
}

void print(const std::string& what, const TResult& r)
{
	std::cout << what << ": ATE " << r.ate << " m (max " << r.maxErr << "), reading P/R/F1 "
	          << r.reading.precision << "/" << r.reading.recall << "/" << r.reading.f1
	          << ", track F1 " << r.track.f1 << ", ARI " << r.ari << ", objects " << r.objects
	          << ", reclassified " << r.reclassified << ", onsets detected " << r.delays.detected
	          << "/" << r.delays.onsets.size() << " max delay " << r.delays.max_delay << "\n";
}
}  // namespace

TEST(ClassifyHighway, AnonymousIdsAreClassifiedAndTheEgoStaysClose)
{
	const TResult labelled = run(scenario("highway.ini"), false);
	const TResult cls = run(scenario("highway_anonymous.ini"), true);
	print("labelled", labelled);
	print("classify", cls);
	EXPECT_GE(cls.track.f1, 0.9);
	EXPECT_GE(cls.reading.f1, 0.9);
	EXPECT_LE(cls.ate, 3 * labelled.ate + 0.03);
}

TEST(ClassifyHighway, ParkedCarDrivingOffIsReclassified)
{
	const TResult labelled = run(scenario("highway_parked_driveoff.ini"), false);
	const TResult cls = run(scenario("highway_parked_driveoff.ini"), true);
	print("labelled", labelled);
	print("classify", cls);
	for (const auto& d : cls.delays.onsets)
		std::cout << "onset object " << d.object << " feature " << d.feature << " at "
		          << d.onset_step << " detected " << d.detect_step << "\n";
	EXPECT_GT(cls.reclassified, 0u);
	EXPECT_LE(cls.ate, 3 * labelled.ate + 0.03);
}

TEST(ClassifyHighway, MissedDetectionsAndClutterDoNotDiverge)
{
	const TResult labelled = run(scenario("highway_clutter.ini"), false);
	const TResult cls = run(scenario("highway_clutter.ini"), true);
	print("labelled", labelled);
	print("classify", cls);
	EXPECT_LT(cls.maxErr, 1.0);
	EXPECT_GE(cls.track.f1, 0.8);
}
