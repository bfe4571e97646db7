#include "dynslam/eval/estimates.h"

#include <set>
#include <stdexcept>
#include <string>

namespace dynslam::eval
{
std::string divergedEstimate(const TRunEstimates& est)
{
	const auto str = [](auto v) { return std::to_string(v); };
	// (maxCoeff may skip a NaN: allFinite first)
	const auto bad = [](const auto& m)
	{ return !m.allFinite() || m.cwiseAbs().maxCoeff() > kDivergedMagnitude; };
	for (const auto& e : est.ego)
		if (bad(e.mean)) return "ego mean at step " + str(e.step);
	for (const auto& l : est.landmarks)
		if (bad(l.mean)) return "mean of landmark " + str(l.id);
	for (const auto& f : est.object_features)
		if (bad(f.mean)) return "mean of object " + str(f.object) + " feature " + str(f.feature);
	for (const auto& p : est.object_poses)
		if (p.mean.size() > 0 && bad(p.mean))
			return "pose of object " + str(p.object) + " at step " + str(p.step);
	return {};
}

void checkEstimates(const TRunEstimates& est)
{
	std::set<int> steps;
	for (const auto& e : est.ego)
	{
		if (e.step < 0)
			throw std::invalid_argument("estimates: ego step " + std::to_string(e.step) + " < 0");
		if (!steps.insert(e.step).second)
			throw std::invalid_argument("estimates: duplicate ego estimate at step " +
			                            std::to_string(e.step));
		if (!e.mean.allFinite())
			throw std::invalid_argument("estimates: non-finite ego mean at step " +
			                            std::to_string(e.step));
	}
	std::set<int32_t> ids;
	for (const auto& l : est.landmarks)
	{
		if (!ids.insert(l.id).second)
			throw std::invalid_argument("estimates: duplicate landmark ID " + std::to_string(l.id));
		if (!l.mean.allFinite())
			throw std::invalid_argument("estimates: non-finite mean of landmark " +
			                            std::to_string(l.id));
	}
	const auto L = static_cast<Eigen::Index>(2 * est.landmarks.size());
	if (est.landmarks_cov.size() != 0 &&
	    (est.landmarks_cov.rows() != L || est.landmarks_cov.cols() != L))
		throw std::invalid_argument("estimates: landmarks_cov is " +
		                            std::to_string(est.landmarks_cov.rows()) + "x" +
		                            std::to_string(est.landmarks_cov.cols()) + ", expected " +
		                            std::to_string(L) + "x" + std::to_string(L));
	for (const auto& f : est.object_features)
		if (!f.mean.allFinite())
			throw std::invalid_argument("estimates: non-finite mean of object " +
			                            std::to_string(f.object) + " feature " +
			                            std::to_string(f.feature));
	for (const auto& p : est.object_poses)
	{
		const std::string name = "estimates: pose of object " + std::to_string(p.object) +
		                         " at step " + std::to_string(p.step);
		const auto n = p.mean.size();
		if (n != 2 && n != 3)
			throw std::invalid_argument(name + " has " + std::to_string(n) +
			                            " entries, not 2 or 3");
		if (p.cov.rows() != n || p.cov.cols() != n)
			throw std::invalid_argument(name + ": covariance size does not match the mean");
		if (!p.mean.allFinite()) throw std::invalid_argument(name + ": non-finite mean");
		const auto v = p.velocity.size();
		if (v != 0 && (v != n || p.velocity_cov.rows() != v || p.velocity_cov.cols() != v))
			throw std::invalid_argument(name +
			                            ": a velocity has as many entries as the pose "
			                            "and a matching covariance");
		if (!p.velocity.allFinite()) throw std::invalid_argument(name + ": non-finite velocity");
	}
	if (est.nis.size() != est.nis_dof.size())
		throw std::invalid_argument("estimates: nis and nis_dof differ in length (" +
		                            std::to_string(est.nis.size()) + " vs " +
		                            std::to_string(est.nis_dof.size()) + ")");
}
}  // namespace dynslam::eval
