#pragma once
/** @file ekf_odometry_bias.h
 * Alg. 7 with an odometry bias block in the state (issue 17 item 2; the model:
 * dynslam/core/models/odometry_bias.h). Pure Eigen, like dynslam/core/ekf_steps.h. */
#include <dynslam/core/ekf_steps.h>

#include <Eigen/Core>

namespace dynslam::ekf
{
/** The bias block's place and random walk. */
struct TOdometryBiasBlock
{
	int index = -1;  ///< state index of b_w (s, if estimated, at index + 1)
	int dim = 1;     ///< 1: (b_w); 2: (b_w, s)
	/** Random-walk densities (variances per second): (rate [rad^2/s^3], scale [1/s]). */
	Eigen::Vector2d q = Eigen::Vector2d::Zero();
};

/** Alg. 7 with the bias: x[0..2] <- x (+) u'(u, b, dt) (models::biasedMotion), the bias
 * unchanged in the mean. With the transition Jacobian Phi (identity except the ego rows
 * [F, J_x_b] at the ego and bias columns), the covariance becomes
 *   P <- Phi P Phi^T + blockdiag(G Sigma_u G^T at the ego, diag(q) dt at the bias),
 * G = J_x_u (the raw increment's Jacobian, i.e. including the scale factor). Only the ego rows
 * and columns and the bias block's diagonal change: O(n). fej_previous_prediction and
 * J_out_x_used as ekf::propagate (first-estimate Jacobians replace the heading column of F;
 * J_x_b is evaluated at the current estimate). dt >= 0 [s].
 * @throws std::out_of_range if the bias block is not inside the state after the ego,
 * std::invalid_argument for dim not 1 or 2, dt < 0 or q < 0. */
void propagateWithBias(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                       const Eigen::Vector3d& u, const Eigen::Matrix3d& Sigma_u,
                       const TOdometryBiasBlock& bias, double dt,
                       const Eigen::Vector3d* fej_previous_prediction = nullptr,
                       Eigen::Matrix3d* J_out_x_used = nullptr);
}  // namespace dynslam::ekf
