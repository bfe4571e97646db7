#pragma once
/** @file multiple_model.h
 * Multiple-model objects (issue 28, `object_model = mm`): an object's state is that of
 * CConstantVelocity ([xi; v], v = (vx, vy, omega)); its prediction mixes four modes
 * (models/mode_mixture.h; doc/state-layout.md "Multiple-model objects"):
 *   - stationary: xi' = xi, v' = 0 (a parked or stopped car), process noise of cv_accel_psd;
 *   - cv: the constant velocity step (models::cvPredict), cv_accel_psd;
 *   - turn: the constant turn rate step (models::ctrvPredict), cv_accel_psd;
 *   - manoeuvre: the constant velocity step with mm_manoeuvre_psd (lane changes, hard brakes).
 * Markov switching: stay with 1 - mm_switch_prob, the rest spread evenly; a new object starts
 * with equal probabilities. Everything else (gate, fallback, initialisation, heading
 * inflation) is CConstantVelocity's. */
#include <dynslam/estimator/constant_velocity.h>

namespace dynslam::estimator
{
class CMultipleModel : public CConstantVelocity
{
public:
	enum Mode : int
	{
		Stationary = 0,
		Cv,
		Turn,
		Manoeuvre,
		NumModes
	};
	/** Validates p.mm_switch_prob and p.mm_manoeuvre_psd (std::invalid_argument). */
	explicit CMultipleModel(const TCvParams& p);
	std::string name() const override { return "mm"; }
	int modeCount() const override { return NumModes; }
	std::string modeName(int mode) const override;
	Eigen::VectorXd predictMode(int mode, const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
	                            Eigen::MatrixXd* Q) const override;
	Eigen::MatrixXd modeTransition() const override;
	Eigen::VectorXd initialModeProbabilities() const override;
};
}  // namespace dynslam::estimator
