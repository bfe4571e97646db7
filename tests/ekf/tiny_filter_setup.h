#pragma once
/** Filter set-up shared by the first-estimate-Jacobian tests (test_fej*.cpp). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include "tiny_scenario.h"

namespace dynslam_test
{
/** The filter's measurement model and noise from the tiny scenario, Sigma_0 = 0, FEJ and the
 * sparse static update on or off, MRPT's naive EKF; then reset(). */
inline void configureTinyFilter(dynslam::CDynamicKFSLAM2D& f,
                                const dynslam_test::TinyScenarioOptions& o, bool fej, bool sparse)
{
	f.options.measurement_model = o.cartesian_noise
	                                  ? dynslam::models::MeasurementModel::Cartesian
	                                  : dynslam::models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = o.cartesian_noise ? o.Sigma_v : o.Sigma_rb;
	f.options.Sigma_0.setZero();
	f.options.sparse_static_update = sparse;
	f.options.first_estimate_jacobians = fej;
	f.KF_options.method = mrpt::bayes::kfEKFNaive;
	f.reset();
}
}  // namespace dynslam_test
