#pragma once
/** @file constant_acceleration.h
 * The constant-acceleration object motion model (`object_model = ca`; doc/state-layout.md
 * "Object-centric motion models"). An object's velocity block is s_v = [v; a] (2d entries for a
 * pose of d = 2 or 3): v the world-frame velocity of the reference point and the turn rate (as
 * in cv), a its time derivative (ax, ay[, alpha]). One step of dt seconds, per axis:
 *
 *     xi' = xi + dt v + dt^2/2 a   (dtheta wrapped),   v' = v + dt a,   a' = a   (+ noise)
 *
 * Process noise: white jerk with spectral densities q = ca_jerk_psd, per axis
 *     Q_i = q_i [dt^5/20 dt^4/8 dt^3/6; dt^4/8 dt^3/3 dt^2/2; dt^3/6 dt^2/2 dt]  on (xi, v, a)_i.
 * Initial velocity block from the first pose xi, e = steps dt after the first sighting:
 * v = xi / e, a = 0, with the prior of a ~ N(0, Sa) and v = xi / e + (e/2) a + n_v,
 * n_v ~ N(0, Sv) (xi / e is the mean velocity over [0, e], which the acceleration shifts by
 * e/2 a at time e): Sigma = [Sv + e^2/4 Sa, e/2 Sa; e/2 Sa, Sa], Sv =
 * diag(cv_velocity_prior_std^2), Sa = diag(ca_accel_prior_std^2). Everything else (dt, gate,
 * fallback, heading inflation) is CConstantVelocity's (the cv_* keys). The model is linear: its
 * Jacobian is exact. */
#include <dynslam/estimator/constant_velocity.h>

namespace dynslam::estimator
{
/** The transition of s = [xi; v; a] (3d entries, d = 2 or 3) over dt: s' and J_out_s (3d x 3d).
 * Throws std::invalid_argument on another size. */
Eigen::VectorXd caPredict(const Eigen::VectorXd& s, double dt, Eigen::MatrixXd* J_out_s = nullptr);

/** White-jerk process noise (3d x 3d, ordered as s = [xi; v; a]) for d = q.size() axes. */
Eigen::MatrixXd caProcessNoise(const Eigen::VectorXd& q, double dt);

class CConstantAcceleration : public CConstantVelocity
{
public:
	/** Throws std::invalid_argument naming the key (ca_jerk_psd, ca_accel_prior_std). */
	explicit CConstantAcceleration(const TCvParams& p);
	std::string name() const override { return "ca"; }
	int velocityDim(int poseDim) const override { return 2 * poseDim; }
	Eigen::VectorXd predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
	                        Eigen::MatrixXd* Q) const override;
	Eigen::VectorXd initialVelocity(const Eigen::VectorXd& xi, int steps, Eigen::MatrixXd* J_v_xi,
	                                Eigen::MatrixXd* Sigma) const override;
};
}  // namespace dynslam::estimator
