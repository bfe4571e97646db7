#pragma once
/** @file gauge.h
 * The prior gauge (issue 13, doc/state-layout.md "The prior gauge"): a global rigid transform
 * delta = (dx, dy, dtheta) of the whole estimate, parameterized as the perturbation of the
 * initial ego pose x_0 = (p0, theta0) (the way Sigma_0 is defined):
 *
 *     T_delta(p) = R(dtheta) (p - p0) + p0 + (dx, dy)       (a world point)
 *
 * moves x_0 to x_0 + delta. It acts on each block of the state as follows (doc/state-layout.md):
 * - ego pose (x, y, theta): (T(p), theta + dtheta), angle wrapped;
 * - a world point (static landmark, f_0, f_t; the body-frame features of cv / ctrv, which
 *   are the world frame at the object's first sighting): T(p);
 * - a world vector (the translation of an object pose xi, whose rotation is about the
 *   centroid of f_0, which moves with T; a world-frame object velocity): R(dtheta) v;
 * - an angle difference (the rotation of xi, the turn rate omega) and the odometry bias:
 *   unchanged.
 * Every reading is invariant under T (tested for the object readings), so the filter may run
 * with x_0 fixed (the gauge) and report P + N Sigma_0 N^T with N = d(state)/d(delta) at 0. */
#include <Eigen/Core>

namespace dynslam::models
{
/** How a block of the state transforms under T_delta. */
enum class GaugeKind
{
	EgoPose,    ///< (x, y, theta)
	Point,      ///< (x, y): a world point
	Vector,     ///< (x, y): a world vector (rotates)
	RelPose,    ///< (dx, dy, dtheta) of xi: translation rotates, rotation unchanged
	Velocity3,  ///< (vx, vy, omega): velocity rotates, turn rate unchanged
	Invariant   ///< any size: unchanged (odometry bias)
};

/** The block after the transform delta (about the initial position p0). */
Eigen::VectorXd gaugeTransform(GaugeKind kind, const Eigen::VectorXd& value,
                               const Eigen::Vector3d& delta, const Eigen::Vector2d& p0);

/** J_block_delta = d gaugeTransform / d delta at delta = 0 (value.size() x 3). */
Eigen::MatrixXd J_block_delta(GaugeKind kind, const Eigen::VectorXd& value,
                              const Eigen::Vector2d& p0);

/** The reported covariance P + N Sigma_0 N^T, with N (P.rows() x 3) stacked from
 * J_block_delta: the uncertain rigid transform of the whole estimate. */
Eigen::MatrixXd addGaugeTerm(const Eigen::MatrixXd& P, const Eigen::MatrixXd& N,
                             const Eigen::Matrix3d& Sigma_0);
}  // namespace dynslam::models
