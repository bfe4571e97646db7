#pragma once
/** @file object_sighting.h
 * (Internal to dynslam::ekf.) One sighting of an object feature, shared by the object updates
 * (object_motion_update.cpp) and the multiple-model likelihoods (object_motion_modes.cpp). */
#include <dynslam/core/models/object_motion.h>

namespace dynslam::detail
{
/** z = h(x (+) s, g(xi, f0)_k); a sensor at the robot origin keeps the code path measured
 * before the sensor offset was supported. */
inline Eigen::Vector2d sighting(models::MeasurementModel m, const Eigen::Vector3d& x,
                                const Eigen::Vector3d& s, const Eigen::VectorXd& xi,
                                const Eigen::Matrix2Xd& f0, int k, models::Matrix23d* J_z_x,
                                Eigen::MatrixXd* J_z_xi, Eigen::MatrixXd* J_z_f0, int founders)
{
	// The pose's centroid: the founders' (features merged in later follow them, object_merge.h).
	const int cc = founders < f0.cols() ? founders : 0;
	return s.isZero(0) ? models::observeObjectFeature(m, x, xi, f0, k, J_z_x, J_z_xi, J_z_f0, cc)
	                   : models::observeObjectFeatureFromSensor(m, x, s, xi, f0, k, J_z_x, J_z_xi,
	                                                            J_z_f0, cc);
}

}  // namespace dynslam::detail
