#include <dynslam/core/models/object_motion.h>
#include <dynslam/estimator/constant_turn_rate.h>

namespace dynslam::estimator
{
Eigen::VectorXd CConstantTurnRate::predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
                                           Eigen::MatrixXd* Q) const
{
	const Eigen::Index d = s.size() / 2;
	if (Q) *Q = models::cvProcessNoise(params().accel_psd.head(d), params().dt);
	return models::ctrvPredict(s, params().dt, J_out_s);
}
}  // namespace dynslam::estimator
