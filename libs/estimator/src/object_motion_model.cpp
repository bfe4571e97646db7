#include <dynslam/core/models/smoothing.h>
#include <dynslam/estimator/object_motion_model.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace dynslam::estimator
{
Eigen::VectorXd IObjectMotionModel::predict(const Eigen::VectorXd&, Eigen::MatrixXd*,
                                            Eigen::MatrixXd*) const
{
	throw std::logic_error(name() + ": has no object state to predict");
}

Eigen::VectorXd IObjectMotionModel::initialVelocity(const Eigen::VectorXd&, int, Eigen::MatrixXd*,
                                                    Eigen::MatrixXd*) const
{
	throw std::logic_error(name() + ": has no object velocity");
}

double IObjectMotionModel::readingGate() const { return std::numeric_limits<double>::infinity(); }

Eigen::VectorXd CNoObjectMotion::residual(const TPseudoMeasurement&,
                                          const std::vector<Eigen::VectorXd>&,
                                          std::vector<Eigen::MatrixXd>*) const
{
	throw std::logic_error("CNoObjectMotion: has no pseudo-measurements");
}

std::vector<TPseudoMeasurement> CPaperSmoothing::select(int32_t object, int step,
                                                        const std::vector<int>& poseSteps,
                                                        int dim) const
{
	// The three poses must be of consecutive steps ending now (an object unseen for a step
	// has no pose then: no smoothing across the gap).
	const auto has = [&](int s)
	{ return std::find(poseSteps.begin(), poseSteps.end(), s) != poseSteps.end(); };
	if (!has(step) || !has(step - 1) || !has(step - 2)) return {};
	TPseudoMeasurement m;
	m.object = object;
	m.steps = {step - 2, step - 1, step};
	m.dim = dim;
	m.R = m_Sigma_s.topLeftCorner(dim, dim);
	return {m};
}

Eigen::VectorXd CPaperSmoothing::residual(const TPseudoMeasurement& m,
                                          const std::vector<Eigen::VectorXd>& poses,
                                          std::vector<Eigen::MatrixXd>* J) const
{
	if (poses.size() != 3) throw std::invalid_argument("CPaperSmoothing: needs three poses");
	if (!J) return models::smoothingResidual(poses[0], poses[1], poses[2]);
	J->resize(3);
	(void)m;
	return models::smoothingResidual(poses[0], poses[1], poses[2], &(*J)[0], &(*J)[1], &(*J)[2]);
}

}  // namespace dynslam::estimator
