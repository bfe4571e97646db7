#pragma once
/** The dynamic EKF's INI for the highway tests (tests/estimator: test_classify_highway,
 * test_effects_ids, test_unknown_ids, the merge tests; the clutter runs of clutter_runs.h):
 * Cartesian readings with the simulator's noise, the action's odometry covariance, a near-exact
 * start. */
#include <dynslam/sim/scenario.h>

#include <string>

namespace dynslam_test
{
/** [DynamicKFSLAM] (with `extraKeys`, "key = value\n" lines, appended to it) and
 * [DynamicKFSLAM_KalmanFilter]. */
inline std::string highwayFilterIni(const std::string& extraKeys = "")
{
	return "[DynamicKFSLAM]\n"
	       "measurement_model = cartesian\n"
	       "Sigma_v = [1e-5 1e-5]\n"
	       "motion_noise = action\n"
	       "Sigma_0 = [1e-5 1e-5 1e-7]\n"
	       "Sigma_xi = [0.1 0.1]\n" +
	       extraKeys +
	       "[DynamicKFSLAM_KalmanFilter]\n"
	       "method = kfEKFNaive\n";
}

/** A scenario INI shipped in config/. */
inline dynslam::sim::TScenarioOptions shippedScenario(const std::string& cfg)
{
	return dynslam::sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/" + cfg);
}
}  // namespace dynslam_test
