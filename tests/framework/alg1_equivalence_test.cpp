/** The whole Alg. 1 run (CAlg1Backend: GN and marginalization steps on a running cost) equals
 * the dynamic EKF (CDynamicKFSLAM2D, a CKalmanFilterCapable subclass) at every step, on the
 * highway scenario and on generated scenarios: mean and covariance within 1e-9 relative
 * (max |A - B| / max |B|), after removing the EKF's pad entries and matching entries by label. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/framework/CAlg1Backend.h>
#include <dynslam/models/se2.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <iostream>
#include <map>

#include "framework_test_utils.h"

using namespace dynslam;
using namespace dynslam::framework;

namespace
{
std::string modelIni(const std::string& extra)
{
	return "[DynamicKFSLAM]\n"
	       "measurement_model = cartesian\n"
	       "Sigma_v = [1e-5 1e-5]\n"
	       "motion_noise = action\n"
	       "Sigma_0 = [1e-6 1e-6 1e-8]\n"
	       "Sigma_xi = [0.1 0.1]\n" +
	       extra +
	       "[DynamicKFSLAM_KalmanFilter]\n"
	       "method = kfEKFNaive\n"
	       "[Framework]\n"
	       "backend = alg1\n";
}

struct TWorst
{
	double mean = 0, cov = 0;
	int steps = 0;
	size_t poses = 0, smoothing = 0, dropped_static = 0, dropped_time_t = 0;
};

/** Runs both on the scenario and compares at every step. */
TWorst runBoth(const sim::TScenarioOptions& so, uint64_t seed, const std::string& extraModel)
{
	const TGroundTruth gt = sim::buildGroundTruth(so);
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, so, seed);
	mrpt::config::CConfigFileMemory ini(modelIni(extraModel));
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(ini, "DynamicKFSLAM");
	TBackendOptions bo;
	bo.loadFromConfigFile(ini, "Framework");
	CAlg1Backend alg(bo);
	TWorst w;
	for (size_t k = 0; k < run.actions.size(); ++k)
	{
		ekf.processActionObservation(run.actions[k], run.frames[k]);
		alg.processActionObservation(run.actions[k], run.frames[k]);
		Eigen::VectorXd xe, xa;
		Eigen::MatrixXd Pe, Pa;
		std::vector<std::string> le, la;
		ekf.getStateWithoutPads(xe, Pe, &le);
		alg.getLabelledState(xa, Pa, la);
		EXPECT_EQ(la.size(), le.size()) << "step " << k;
		if (la.size() != le.size()) break;
		std::map<std::string, int> where;
		for (size_t i = 0; i < le.size(); ++i) where[le[i]] = int(i);
		std::vector<int> perm;
		for (const auto& l : la)
		{
			const auto it = where.find(l);
			EXPECT_TRUE(it != where.end()) << "step " << k << ": label " << l << " not in the EKF";
			if (it == where.end()) return w;
			perm.push_back(it->second);
		}
		Eigen::VectorXd dx = xa - xe(perm);
		for (size_t i = 0; i < la.size(); ++i)
			if (la[i].find("theta") != std::string::npos) dx[i] = models::wrapToPi(dx[i]);
		const double em = dx.cwiseAbs().maxCoeff() / std::max(xe.cwiseAbs().maxCoeff(), 1e-300);
		const double ec = dynslam_test::relErr(Pa, Pe(perm, perm));
		w.mean = std::max(w.mean, em);
		w.cov = std::max(w.cov, ec);
		++w.steps;
		const TStepReport& ra = alg.getLastStepReport();
		w.poses += ra.object_poses_added;
		w.smoothing += ra.smoothing_updates;
		w.dropped_static += ra.dropped_static;
		w.dropped_time_t += ra.dropped_time_t;
		EXPECT_EQ(ra.smoothing_updates, ekf.getLastStepReport().smoothing_updates);
		EXPECT_EQ(ra.dropped_static, ekf.getLastStepReport().dropped_static);
		EXPECT_EQ(alg.getLastStepReport().object_poses_added,
		          ekf.getLastStepReport().object_poses_added);
		EXPECT_EQ(alg.getLastStepReport().dropped_poses, ekf.getLastStepReport().dropped_poses);
		EXPECT_NEAR(alg.getLastStepReport().nis_static, ekf.getLastStepReport().nis_static,
		            1e-6 * std::max(1.0, ekf.getLastStepReport().nis_static));
	}
	return w;
}

sim::TScenarioOptions scenario(const std::string& file, int steps)
{
	sim::TScenarioOptions so = sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/" + file);
	if (steps > 0) so.steps = steps;
	return so;
}

TWorst report(const char* what, const TWorst& w)
{
	std::cout << "[alg1 vs EKF] " << what << ": " << w.steps << " steps, worst mean rel. error "
	          << w.mean << ", worst covariance rel. error " << w.cov << "\n";
	EXPECT_GT(w.steps, 0);
	EXPECT_LT(w.mean, 1e-9) << what;
	EXPECT_LT(w.cov, 1e-9) << what;
	EXPECT_GT(w.poses, 0u) << what;
	return w;
}
}  // namespace

TEST(Alg1, WholeRunEquivalenceHighway)
{
	report("highway (120 steps)", runBoth(scenario("highway.ini", -1), 1, ""));
}

TEST(Alg1, WholeRunEquivalenceGeneratedScenarios)
{
	const auto so = scenario("generated_small_scenario.ini", 18);
	report("generated, defaults", runBoth(so, 2, ""));
	const TWorst keep =
	    report("generated, keep time-t features", runBoth(so, 3, "drop_time_t_features = false\n"));
	EXPECT_GT(keep.dropped_time_t, 0u);  // stale f_t replaced (marginalized) when seen again
	const TWorst sm = report(
	    "generated, smoothing, K = 3",
	    runBoth(so, 4, "smoothing = true\nSigma_s = [1e-2 1e-2 1e-3]\nkeep_last_poses = 3\n"));
	EXPECT_GT(sm.smoothing, 0u);
	const TWorst dr = report("generated, static drop after 2 unseen steps",
	                         runBoth(so, 5, "drop_static_after_unseen_steps = 2\n"));
	EXPECT_GT(dr.dropped_static, 0u);
}

TEST(Alg1, WholeRunEquivalenceRangeBearingAndConfigNoise)
{
	auto so = scenario("generated_small_scenario.ini", 18);
	report(
	    "generated, range-bearing, Sigma_w from config",
	    runBoth(so, 6,
	            "measurement_model = range_bearing\nSigma_v = [1e-4 1e-6]\nmotion_noise = config\n"
	            "Sigma_w = [1e-5 1e-5 1e-7]\n"));
	report("generated, MRPT's skip of the prediction on an empty map",
	       runBoth(so, 7, "skip_prediction_on_empty_map = true\n"));
}

TEST(Alg1, WholeRunEquivalenceSensorNotAtTheOrigin)
{
	// The simulator takes the readings from x (+) s and writes s to sensorLocationOnRobot; both
	// filters model z = h(x (+) s, f), with the Jacobian through the composition.
	auto so = scenario("generated_small_scenario.ini", 18);
	so.sensor_pose = Eigen::Vector3d(0.3, -0.1, 0.2);
	report("generated, sensor at (0.3, -0.1, 0.2), cartesian", runBoth(so, 8, ""));
	report("generated, sensor at (0.3, -0.1, 0.2), range-bearing, smoothing",
	       runBoth(so, 9,
	               "measurement_model = range_bearing\nSigma_v = [1e-4 1e-6]\n"
	               "smoothing = true\nSigma_s = [1e-2 1e-2 1e-3]\nkeep_last_poses = 3\n"));
}

TEST(Alg1, BadInputWindowSizeZeroAndSingularPrior)
{
	mrpt::config::CConfigFileMemory ini(modelIni("") + "window_size = 0\n");
	TBackendOptions bo;
	try
	{
		bo.loadFromConfigFile(ini, "Framework");
		FAIL() << "no exception";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("window_size"), std::string::npos) << e.what();
	}
	// The framework needs Sigma_0^-1: a zero Sigma_0 is rejected with a clear message.
	TBackendOptions z = defaultBackendOptions("alg1");
	z.model.Sigma_0.setZero();
	EXPECT_THROW(CAlg1Backend{z}, std::invalid_argument);
	z.model.Sigma_0 = Eigen::Matrix3d::Identity() * 1e-6;
	z.window_size = 0;
	EXPECT_THROW(CAlg1Backend{z}, std::invalid_argument);
}
