#include "dynslam/eval/align.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::eval
{
TSE2Alignment alignSE2(const std::vector<Eigen::Vector2d>& est,
                       const std::vector<Eigen::Vector2d>& truth)
{
	if (est.size() != truth.size())
		throw std::invalid_argument("alignSE2: " + std::to_string(est.size()) +
		                            " estimated points for " + std::to_string(truth.size()) +
		                            " true points");
	if (est.empty()) throw std::invalid_argument("alignSE2: no point to align");
	const double n = static_cast<double>(est.size());
	Eigen::Vector2d meanEst = Eigen::Vector2d::Zero(), meanTruth = Eigen::Vector2d::Zero();
	for (size_t i = 0; i < est.size(); ++i)
	{
		meanEst += est[i];
		meanTruth += truth[i];
	}
	meanEst /= n;
	meanTruth /= n;
	double dot = 0, cross = 0;
	for (size_t i = 0; i < est.size(); ++i)
	{
		const Eigen::Vector2d p = est[i] - meanEst, r = truth[i] - meanTruth;
		dot += p.dot(r);
		cross += p.x() * r.y() - p.y() * r.x();
	}
	TSE2Alignment a;
	const double theta = (dot == 0 && cross == 0) ? 0.0 : std::atan2(cross, dot);
	const Eigen::Matrix2d R = Eigen::Rotation2Dd(theta).toRotationMatrix();
	const Eigen::Vector2d t = meanTruth - R * meanEst;
	a.q << t.x(), t.y(), theta;
	double sumSq = 0;
	for (size_t i = 0; i < est.size(); ++i) sumSq += (truth[i] - (R * est[i] + t)).squaredNorm();
	a.rms = std::sqrt(sumSq / n);
	return a;
}
}  // namespace dynslam::eval
