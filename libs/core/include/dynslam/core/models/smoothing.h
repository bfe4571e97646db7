#pragma once
/** @file smoothing.h
 * Smoothing function s of the paper (Section II step 4, Alg. 6): the change of the object's
 * motion between two consecutive steps,
 *
 *     s(xi_{t-2}, xi_{t-1}, xi_t) = (xi_t - xi_{t-1}) - (xi_{t-1} - xi_{t-2}),
 *
 * with every angle difference wrapped to (-pi, pi]. The paper prints a product of the two
 * differences; a product of two first differences is not a smoothness residual (it is zero
 * whenever the object stands still once), so we read it as this second difference (see
 * doc/paper-map.md). Works for 3-dof poses (dx, dy, dtheta: the last component is an angle)
 * and 2-dof translation-only poses (no angle). */
#include <Eigen/Core>

namespace dynslam::models
{
/** s(a, b, c) for poses of dimension d = a.size() (2 or 3); J_s_a = I, J_s_b = -2I, J_s_c = I. */
Eigen::VectorXd smoothingResidual(const Eigen::VectorXd& xi_tm2, const Eigen::VectorXd& xi_tm1,
                                  const Eigen::VectorXd& xi_t, Eigen::MatrixXd* J_s_tm2 = nullptr,
                                  Eigen::MatrixXd* J_s_tm1 = nullptr,
                                  Eigen::MatrixXd* J_s_t = nullptr);
}  // namespace dynslam::models
