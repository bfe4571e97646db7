#include <dynslam/core/ekf_odometry_bias.h>
#include <dynslam/core/models/odometry_bias.h>

#include <stdexcept>
#include <string>

namespace dynslam::ekf
{
void propagateWithBias(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                       const Eigen::Vector3d& u, const Eigen::Matrix3d& Sigma_u,
                       const TOdometryBiasBlock& bias, double dt,
                       const Eigen::Vector3d* fej_previous_prediction,
                       Eigen::Matrix3d* J_out_x_used)
{
	const Eigen::Index n = x.size(), bi = bias.index, d = bias.dim;
	if (P.rows() != n || P.cols() != n)
		throw std::invalid_argument("propagateWithBias: P does not match x");
	if (d != 1 && d != 2) throw std::invalid_argument("propagateWithBias: bias dim must be 1 or 2");
	if (bi < 3 || bi + d > n)
		throw std::out_of_range("propagateWithBias: bias index " + std::to_string(bi) +
		                        " outside the state after the ego (size " + std::to_string(n) +
		                        ")");
	if (!(dt >= 0) || !(bias.q.array() >= 0).all())
		throw std::invalid_argument("propagateWithBias: dt and q must be >= 0");
	const Eigen::VectorXd b = x.segment(bi, d);
	Eigen::Matrix3d F, G;
	Eigen::MatrixXd J_x_b;
	x.head<3>() = models::biasedMotion(x.head<3>(), b, u, dt, &F, &J_x_b, &G);
	if (fej_previous_prediction)
	{
		F(0, 2) = -(x[1] - (*fej_previous_prediction)[1]);
		F(1, 2) = x[0] - (*fej_previous_prediction)[0];
	}
	if (J_out_x_used) *J_out_x_used = F;
	// T = the new ego rows of Phi P: F P[e, :] + J_x_b P[b, :] (3 x n).
	const Eigen::MatrixXd T = F * P.topRows(3) + J_x_b * P.middleRows(bi, d);
	Eigen::Matrix3d Pee = T.leftCols(3) * F.transpose() + T.middleCols(bi, d) * J_x_b.transpose() +
	                      G * Sigma_u * G.transpose();
	Pee = 0.5 * (Pee + Pee.transpose()).eval();
	P.topRows(3) = T;
	P.leftCols(3) = T.transpose();
	P.topLeftCorner<3, 3>() = Pee;
	for (Eigen::Index i = 0; i < d; ++i) P(bi + i, bi + i) += bias.q[i] * dt;
}
}  // namespace dynslam::ekf
