#pragma once
/** @file odometry_bias.h
 * Odometry bias model (issue 17 item 2, doc/state-layout.md "Odometry bias"): the odometry
 * increment u = (dx, dy, dtheta) of one step of duration dt [s] (robot frame) is corrected by a
 * bias b estimated in the state,
 *
 *   u' = ((1 - s) dx, (1 - s) dy, dtheta - b_w dt),
 *
 * with b_w [rad/s] the angular-rate bias of the odometry and s [-] the scale-factor error of
 * its translation (the odometry reports 1 / (1 - s) times the travelled distance). The bias
 * block holds b = (b_w) (kind `rate`, 1 entry, s = 0) or b = (b_w, s) (kind `rate_scale`,
 * 2 entries). The ego moves by x_{k+1} = x_k (+) u'; b follows a random walk,
 * b_{k+1} = b_k + w_b, w_b ~ N(0, diag(q) dt), q = (rate_rw^2, scale_rw^2) [rad^2/s^3, 1/s]. */
#include <Eigen/Core>

namespace dynslam::models
{
/** The corrected increment u' of u by the bias b (b.size() = 1: (b_w); 2: (b_w, s)).
 * J_u'_u = diag(1 - s, 1 - s, 1) (3x3), J_u'_b = 3 x b.size(). */
Eigen::Vector3d correctedIncrement(const Eigen::Vector3d& u, const Eigen::VectorXd& b, double dt,
                                   Eigen::Matrix3d* J_uc_u = nullptr,
                                   Eigen::MatrixXd* J_uc_b = nullptr);

/** The biased motion x_{k+1} = x (+) u'(u, b, dt), angle wrapped, with J_out_x (3x3),
 * J_out_b (3 x b.size()) and J_out_u (3x3, the raw increment's). */
Eigen::Vector3d biasedMotion(const Eigen::Vector3d& x, const Eigen::VectorXd& b,
                             const Eigen::Vector3d& u, double dt,
                             Eigen::Matrix3d* J_out_x = nullptr, Eigen::MatrixXd* J_out_b = nullptr,
                             Eigen::Matrix3d* J_out_u = nullptr);
}  // namespace dynslam::models
