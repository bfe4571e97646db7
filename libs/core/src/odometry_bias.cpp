#include <dynslam/core/models/odometry_bias.h>
#include <dynslam/core/models/se2.h>

#include <stdexcept>

namespace dynslam::models
{
Eigen::Vector3d correctedIncrement(const Eigen::Vector3d& u, const Eigen::VectorXd& b, double dt,
                                   Eigen::Matrix3d* J_uc_u, Eigen::MatrixXd* J_uc_b)
{
	if (b.size() != 1 && b.size() != 2)
		throw std::invalid_argument("correctedIncrement: the bias has 1 or 2 entries");
	const double s = b.size() == 2 ? b[1] : 0.0;
	const Eigen::Vector3d uc((1 - s) * u[0], (1 - s) * u[1], u[2] - b[0] * dt);
	if (J_uc_u) *J_uc_u = Eigen::Vector3d(1 - s, 1 - s, 1).asDiagonal();
	if (J_uc_b)
	{
		J_uc_b->setZero(3, b.size());
		(*J_uc_b)(2, 0) = -dt;
		if (b.size() == 2)
		{
			(*J_uc_b)(0, 1) = -u[0];
			(*J_uc_b)(1, 1) = -u[1];
		}
	}
	return uc;
}

Eigen::Vector3d biasedMotion(const Eigen::Vector3d& x, const Eigen::VectorXd& b,
                             const Eigen::Vector3d& u, double dt, Eigen::Matrix3d* J_out_x,
                             Eigen::MatrixXd* J_out_b, Eigen::Matrix3d* J_out_u)
{
	Eigen::Matrix3d J_uc_u;
	Eigen::MatrixXd J_uc_b;
	const Eigen::Vector3d uc = correctedIncrement(u, b, dt, &J_uc_u, &J_uc_b);
	Eigen::Matrix3d J_out_uc;
	const Eigen::Vector3d out = composePose(x, uc, J_out_x, &J_out_uc);
	if (J_out_b) *J_out_b = J_out_uc * J_uc_b;
	if (J_out_u) *J_out_u = J_out_uc * J_uc_u;
	return out;
}
}  // namespace dynslam::models
