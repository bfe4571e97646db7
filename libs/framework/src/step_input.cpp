#include <dynslam/framework/step_input.h>
#include <dynslam/landmark_ids.h>

#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace dynslam::framework
{
TStepInput parseStepInput(
	const mrpt::obs::CActionCollection::Ptr& action, const mrpt::obs::CSensoryFrame::Ptr& SF,
	models::MeasurementModel model, const char* who)
{
	const std::string w = who;
	if (!action) throw std::runtime_error(w + ": null action collection");
	const auto mov = action->getBestMovementEstimation();
	if (!mov) throw std::runtime_error(w + ": the action collection holds no CActionRobotMovement2D");
	mrpt::poses::CPosePDFGaussian inc(*mov->poseChange);
	TStepInput in;
	in.u = Eigen::Vector3d(inc.mean.x(), inc.mean.y(), inc.mean.phi());
	in.U = inc.cov.asEigen();
	if (!in.u.allFinite() || !in.U.allFinite())
		throw std::runtime_error(w + ": odometry increment or covariance not finite");
	if (!SF) throw std::runtime_error(w + ": null sensory frame");
	const auto obs = SF->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	if (!obs) return in;
	const auto& sp = obs->sensorLocationOnRobot;
	if (std::abs(sp.x()) + std::abs(sp.y()) + std::abs(sp.z()) + std::abs(sp.yaw()) +
			std::abs(sp.pitch()) + std::abs(sp.roll()) >
		0)
		throw std::runtime_error(w + ": sensorLocationOnRobot must be the identity");
	in.max_range = obs->maxSensorDistance;
	std::set<int32_t> seen;
	for (size_t i = 0; i < obs->sensedData.size(); ++i)
	{
		const auto& m = obs->sensedData[i];
		const std::string where =
			"measurement " + std::to_string(i) + " (landmark ID " + std::to_string(m.landmarkID) + ")";
		if (!std::isfinite(m.range) || !std::isfinite(m.yaw) || !std::isfinite(m.pitch))
			throw std::runtime_error(w + ": NaN or Inf in " + where);
		if (m.pitch != 0) throw std::runtime_error(w + ": non-zero pitch in " + where);
		if (!(m.range >= 0)) throw std::runtime_error(w + ": negative range in " + where);
		if (model == models::MeasurementModel::RangeBearing && m.range == 0)
			throw std::runtime_error(w + ": zero range in " + where);
		const auto kind = ids::classify(m.landmarkID);
		if (kind == ids::IdKind::Invalid)
			throw std::runtime_error(w + ": " + where + " is in no known ID range");
		if (!seen.insert(m.landmarkID).second) throw std::runtime_error(w + ": duplicate " + where);
		const TMeasurement tm{m.landmarkID, models::fromRangeBearing(model, m.range, m.yaw)};
		(kind == ids::IdKind::Static ? in.statics : in.objects).push_back(tm);
	}
	return in;
}
}  // namespace dynslam::framework
