#pragma once
/** The highway set-up of the cv tests that run the paper's highway at level w3v1
 * (test_object_model_cv_heading.cpp, test_object_model_cv_ego_delay.cpp). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>

#include <string>

namespace dynslam_test
{
/** The paper's highway (datasets/highway_scenario.ini) at level w3v1: odometry noise
 * diag(1e-4, 1e-4, 1e-6) per step, readings 1e-6 m^2, the prior Sigma_0 = Sigma_w of Table I
 * (the level where the objects' readings move the ego most). */
inline dynslam::sim::TScenarioOptions highwayW3v1()
{
	dynslam::sim::TScenarioOptions o =
	    dynslam::sim::loadScenario(DYNSLAM_DATASETS_DIR "/highway_scenario.ini");
	o.setNoiseLevel("w3v1");
	return o;
}

/** The level's noise and prior, Cartesian readings, `model` with the white acceleration `psd`
 * and the velocity prior std [0.5 0.5 0.05]; the caller sets its own keys and calls reset(). */
inline void configureHighwayCv(dynslam::CDynamicKFSLAM2D& f,
                               const dynslam::sim::TScenarioOptions& o, const std::string& model,
                               const Eigen::Vector3d& psd)
{
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = dynslam::models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0 = o.Sigma_0;
	f.options.object_model = model;
	f.options.cv.dt = o.dt;
	f.options.cv.accel_psd = psd;
	f.options.cv.velocity_prior_std = Eigen::Vector3d(0.5, 0.5, 0.05);
}

/** The filter's whole estimate as one vector: the mean without pads, then its covariance
 * (column-major), for bit-for-bit comparisons of two runs. */
inline Eigen::VectorXd meanAndCovariance(const dynslam::CDynamicKFSLAM2D& f)
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	f.getStateWithoutPads(x, P);
	Eigen::VectorXd out(x.size() + P.size());
	out << x, P.reshaped();
	return out;
}
}  // namespace dynslam_test
