#include <dynslam/core/models/object_motion.h>
#include <dynslam/estimator/constant_velocity.h>

#include <cmath>
#include <stdexcept>

namespace dynslam::estimator
{
void TCvParams::validate() const
{
	if (!(dt > 0) || !std::isfinite(dt))
		throw std::invalid_argument("cv_dt = " + std::to_string(dt) + ": must be > 0");
	if (!accel_psd.allFinite() || (accel_psd.array() < 0).any())
		throw std::invalid_argument("cv_accel_psd: must be finite and >= 0");
	if (!velocity_prior_std.allFinite() || (velocity_prior_std.array() <= 0).any())
		throw std::invalid_argument(
		    "cv_velocity_prior_std: must be finite and > 0 (the velocity prior must be positive "
		    "definite)");
	if (!(gate > 0)) throw std::invalid_argument("cv gate threshold: must be > 0");
	if (!(heading_inflation >= 0) || !std::isfinite(heading_inflation))
		throw std::invalid_argument("cv_heading_inflation = " + std::to_string(heading_inflation) +
		                            ": must be finite and >= 0 (0 = off)");
	if (fallback_steps < 0)
		throw std::invalid_argument("cv_fallback_steps = " + std::to_string(fallback_steps) +
		                            ": must be >= 0 (0 = off)");
}

CConstantVelocity::CConstantVelocity(const TCvParams& p) : m_p(p) { m_p.validate(); }

bool CConstantVelocity::reportGating(int32_t object, bool allGatedOut)
{
	if (m_p.fallback_steps == 0) return false;
	if (!allGatedOut)
	{
		m_gatedSteps.erase(object);
		return false;
	}
	if (++m_gatedSteps[object] < m_p.fallback_steps) return false;
	m_gatedSteps.erase(object);  // lost: its next velocity starts afresh
	++m_fallbacks;
	return true;
}

Eigen::VectorXd CConstantVelocity::residual(const TPseudoMeasurement&,
                                            const std::vector<Eigen::VectorXd>&,
                                            std::vector<Eigen::MatrixXd>*) const
{
	throw std::logic_error("CConstantVelocity: has no pseudo-measurements");
}

Eigen::VectorXd CConstantVelocity::predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
                                           Eigen::MatrixXd* Q) const
{
	const Eigen::Index d = s.size() / 2;
	if (Q) *Q = models::cvProcessNoise(m_p.accel_psd.head(d), m_p.dt);
	return models::cvPredict(s, m_p.dt, J_out_s);
}

Eigen::VectorXd CConstantVelocity::initialVelocity(const Eigen::VectorXd& xi, int steps,
                                                   Eigen::MatrixXd* J_v_xi,
                                                   Eigen::MatrixXd* Sigma) const
{
	if (steps < 1)
		throw std::invalid_argument("CConstantVelocity: an object seen once has no velocity");
	if (Sigma)
		*Sigma = m_p.velocity_prior_std.head(xi.size()).array().square().matrix().asDiagonal();
	return models::cvInitialVelocity(xi, double(steps) * m_p.dt, J_v_xi);
}
}  // namespace dynslam::estimator
