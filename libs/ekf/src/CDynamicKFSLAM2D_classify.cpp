/** CDynamicKFSLAM2D: the filter's own innovation of a static reading for the classifying
 * router (classify_static_test = map, doc/results/classification.md). */
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

namespace dynslam
{
bool CDynamicKFSLAM2D::staticInnovation(int32_t id, const Eigen::Vector2d& z,
                                        estimator::TStaticInnovation& out) const
{
	const auto it = m_staticBlock.find(id);
	// With the odometry bias the prediction also moves with the bias block: not modelled here.
	if (it == m_staticBlock.end() || options.odometry_bias.enabled()) return false;
	const Eigen::Index k = m_layout.first(it->second);
	const auto P = cov();
	const Eigen::Vector3d x(m_xkk[0], m_xkk[1], m_xkk[2]);
	const Eigen::Vector2d f(m_xkk[size_t(k)], m_xkk[size_t(k) + 1]);
	// The ego predicted as propagateEgo() will (without first-estimate Jacobians).
	Eigen::Matrix3d J_x_x, J_x_u;
	const bool skip = options.skip_prediction_on_empty_map && mapEmpty();
	const Eigen::Vector3d xp = skip ? x : models::composePose(x, m_in.u, &J_x_x, &J_x_u);
	if (skip) J_x_x.setIdentity(), J_x_u.setZero();
	const Eigen::Matrix3d& U = options.motion_noise_from_action ? m_in.U : options.Sigma_w;
	Eigen::Matrix<double, 5, 5> C;
	C.topLeftCorner<3, 3>() =
	    J_x_x * P.topLeftCorner(3, 3) * J_x_x.transpose() + J_x_u * U * J_x_u.transpose();
	C.topRightCorner<3, 2>() = J_x_x * P.block(0, k, 3, 2);
	C.bottomLeftCorner<2, 3>() = C.topRightCorner<3, 2>().transpose();
	C.bottomRightCorner<2, 2>() = P.block(k, k, 2, 2);
	models::Matrix23d J_z_x;
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector2d zhat = models::observeFromSensor(options.measurement_model, xp,
	                                                       m_in.sensor_pose, f, &J_z_x, &J_z_f);
	Eigen::Matrix<double, 2, 5> H;
	H << J_z_x, J_z_f;
	out.nu = models::innovation(options.measurement_model, z, zhat);
	out.S = H * C * H.transpose() + options.Sigma_v;
	out.J_z_f = J_z_f;
	return true;
}
}  // namespace dynslam
