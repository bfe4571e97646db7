#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/constant_acceleration.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
Eigen::VectorXd caPredict(const Eigen::VectorXd& s, double dt, Eigen::MatrixXd* J_out_s)
{
	if (s.size() != 6 && s.size() != 9)
		throw std::invalid_argument("caPredict: state of 6 or 9 entries, not " +
		                            std::to_string(s.size()));
	const Eigen::Index d = s.size() / 3;
	Eigen::VectorXd out = s;
	out.head(d) += dt * s.segment(d, d) + 0.5 * dt * dt * s.tail(d);
	out.segment(d, d) += dt * s.tail(d);
	if (d == 3) out[2] = models::wrapToPi(out[2]);
	if (J_out_s)
	{
		J_out_s->setIdentity(3 * d, 3 * d);
		J_out_s->block(0, d, d, d).diagonal().setConstant(dt);
		J_out_s->block(d, 2 * d, d, d).diagonal().setConstant(dt);
		J_out_s->block(0, 2 * d, d, d).diagonal().setConstant(0.5 * dt * dt);
	}
	return out;
}

Eigen::MatrixXd caProcessNoise(const Eigen::VectorXd& q, double dt)
{
	const Eigen::Index d = q.size();
	Eigen::Matrix3d unit;  // per unit spectral density, on (xi_i, v_i, a_i)
	const double t2 = dt * dt, t3 = t2 * dt, t4 = t3 * dt, t5 = t4 * dt;
	unit << t5 / 20, t4 / 8, t3 / 6, t4 / 8, t3 / 3, t2 / 2, t3 / 6, t2 / 2, dt;
	Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(3 * d, 3 * d);
	for (Eigen::Index i = 0; i < d; ++i)
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) Q(r * d + i, c * d + i) = q[i] * unit(r, c);
	return Q;
}

CConstantAcceleration::CConstantAcceleration(const TCvParams& p) : CConstantVelocity(p)
{
	if (!p.jerk_psd.allFinite() || (p.jerk_psd.array() < 0).any())
		throw std::invalid_argument("ca_jerk_psd: must be finite and >= 0");
	if (!p.accel_prior_std.allFinite() || (p.accel_prior_std.array() <= 0).any())
		throw std::invalid_argument(
		    "ca_accel_prior_std: must be finite and > 0 (the acceleration prior must be positive "
		    "definite)");
}

Eigen::VectorXd CConstantAcceleration::predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
                                               Eigen::MatrixXd* Q) const
{
	const Eigen::Index d = s.size() / 3;
	if (Q) *Q = caProcessNoise(params().jerk_psd.head(d), params().dt);
	return caPredict(s, params().dt, J_out_s);
}

Eigen::VectorXd CConstantAcceleration::initialVelocity(const Eigen::VectorXd& xi, int steps,
                                                       Eigen::MatrixXd* J_v_xi,
                                                       Eigen::MatrixXd* Sigma) const
{
	if (steps < 1)
		throw std::invalid_argument("CConstantAcceleration: an object seen once has no velocity");
	const Eigen::Index d = xi.size();
	const double e = double(steps) * params().dt;
	if (Sigma)
	{
		const Eigen::MatrixXd Sv =
		    params().velocity_prior_std.head(d).array().square().matrix().asDiagonal();
		const Eigen::MatrixXd Sa =
		    params().accel_prior_std.head(d).array().square().matrix().asDiagonal();
		Sigma->resize(2 * d, 2 * d);
		*Sigma << Sv + 0.25 * e * e * Sa, 0.5 * e * Sa, 0.5 * e * Sa, Sa;
	}
	if (J_v_xi)
	{
		J_v_xi->setZero(2 * d, d);
		J_v_xi->topRows(d).diagonal().setConstant(1.0 / e);
	}
	Eigen::VectorXd v = Eigen::VectorXd::Zero(2 * d);
	v.head(d) = xi / e;
	return v;
}
}  // namespace dynslam::estimator
