#pragma once
/** The filter setup of the object-model tests (test_object_model_ctrv.cpp,
 * test_object_model_bad_input.cpp): Cartesian readings with the tiny scenario's noise, the
 * ego start known exactly, near-rigid objects, and the cv / ctrv keys used by both. */
#include <dynslam/CDynamicKFSLAM2D.h>

#include <string>

#include "tiny_scenario.h"

namespace dynslam_test
{
inline void configureObjectModel(dynslam::CDynamicKFSLAM2D& f, const TinyScenarioOptions& o,
                                 const std::string& model)
{
	f.options.measurement_model = dynslam::models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0.setZero();
	f.options.Sigma_xi = Eigen::Matrix2d::Identity() * 1e-6;
	f.options.object_model = model;
	f.options.cv.dt = 1.0;
	f.options.cv.accel_psd = Eigen::Vector3d(1e-4, 1e-4, 1e-6);
	f.options.cv.velocity_prior_std = Eigen::Vector3d(0.1, 0.1, 0.05);
	f.reset();
}
}  // namespace dynslam_test
