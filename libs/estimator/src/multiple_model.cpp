#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/estimator/multiple_model.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
CMultipleModel::CMultipleModel(const TCvParams& p) : CConstantVelocity(p)
{
	if (!(p.mm_switch_prob > 0 && p.mm_switch_prob < 1))
		throw std::invalid_argument("mm_switch_prob = " + std::to_string(p.mm_switch_prob) +
		                            ": must be in (0, 1)");
	if (!p.mm_manoeuvre_psd.allFinite() || (p.mm_manoeuvre_psd.array() <= 0).any())
		throw std::invalid_argument("mm_manoeuvre_psd: must be finite and > 0");
}

std::string CMultipleModel::modeName(int mode) const
{
	switch (mode)
	{
		case Stationary:
			return "stationary";
		case Cv:
			return "cv";
		case Turn:
			return "turn";
		case Manoeuvre:
			return "manoeuvre";
		default:
			throw std::out_of_range("CMultipleModel: no mode " + std::to_string(mode));
	}
}

Eigen::VectorXd CMultipleModel::predictMode(int mode, const Eigen::VectorXd& s,
                                            Eigen::MatrixXd* J_out_s, Eigen::MatrixXd* Q) const
{
	const Eigen::Index d = s.size() / 2;
	const double dt = params().dt;
	switch (mode)
	{
		case Stationary:
		{
			if (s.size() != 4 && s.size() != 6)
				throw std::invalid_argument("CMultipleModel: s must have 4 or 6 entries");
			if (Q) *Q = models::cvProcessNoise(params().accel_psd.head(d), dt);
			if (J_out_s)
			{
				*J_out_s = Eigen::MatrixXd::Zero(2 * d, 2 * d);
				J_out_s->topLeftCorner(d, d).setIdentity();
			}
			Eigen::VectorXd out = s;
			out.tail(d).setZero();
			return out;
		}
		case Cv:
		case Manoeuvre:
			if (Q)
				*Q = models::cvProcessNoise(
				    (mode == Cv ? params().accel_psd : params().mm_manoeuvre_psd).head(d), dt);
			return models::cvPredict(s, dt, J_out_s);
		case Turn:
			if (Q) *Q = models::cvProcessNoise(params().accel_psd.head(d), dt);
			return models::ctrvPredict(s, dt, J_out_s);
		default:
			throw std::out_of_range("CMultipleModel: no mode " + std::to_string(mode));
	}
}

Eigen::MatrixXd CMultipleModel::modeTransition() const
{
	return models::uniformSwitching(NumModes, params().mm_switch_prob);
}

Eigen::VectorXd CMultipleModel::initialModeProbabilities() const
{
	return Eigen::VectorXd::Constant(NumModes, 1.0 / NumModes);
}
}  // namespace dynslam::estimator
