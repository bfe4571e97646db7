#pragma once
/** @file constant_turn_rate.h
 * The constant turn rate and velocity object motion model (issue 13, `object_model = ctrv`):
 * the state, the updates, the gate, the inflation rule, the initialisation and the options
 * (the cv_* keys) are those of CConstantVelocity; only the process model differs
 * (models::ctrvPredict: the velocity turns at the turn rate, the reference point moves on a
 * circle). The process noise is CV's white acceleration on (xi, v) (an approximation: the
 * acceleration is not rotated into the body frame). */
#include <dynslam/estimator/constant_velocity.h>

namespace dynslam::estimator
{
class CConstantTurnRate : public CConstantVelocity
{
public:
	explicit CConstantTurnRate(const TCvParams& p) : CConstantVelocity(p) {}
	std::string name() const override { return "ctrv"; }
	Eigen::VectorXd predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
	                        Eigen::MatrixXd* Q) const override;
};
}  // namespace dynslam::estimator
