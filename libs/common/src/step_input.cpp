#include <dynslam/common/detection_boxes.h>
#include <dynslam/common/detection_groups.h>
#include <dynslam/common/step_input.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/system/datetime.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynslam
{
namespace
{
void checkOdometryCov(const Eigen::Matrix3d& U, const std::string& who)
{
	const Eigen::Matrix3d Us = 0.5 * (U + U.transpose());
	if ((U - Us).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, U.cwiseAbs().maxCoeff()) ||
	    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Us).eigenvalues().minCoeff() <
	        -1e-12 * std::max(1.0, U.norm()))
		throw std::runtime_error(who +
		                         ": odometry covariance is not symmetric positive semi-definite");
}
}  // namespace

Eigen::Vector3d sensorPoseOnRobot(const mrpt::poses::CPose3D& p, const std::string& who)
{
	for (int i = 0; i < 6; ++i)
		if (!std::isfinite(p[i]))
			throw std::runtime_error(who +
			                         ": the bearing-range observation's sensorLocationOnRobot is "
			                         "not finite (x y z yaw pitch roll = " +
			                         p.asString() + ")");
	// A tilted sensor does not measure bearings in the plane of the map: 2-D SLAM only. A height
	// (z) is harmless: with pitch 0 every reading lies in the sensor's horizontal plane, and
	// MRPT's CRangeBearingKFSLAM2D ignores it too (CPose2D(sensorLocationOnRobot)).
	if (std::abs(p.pitch()) > 1e-9 || std::abs(p.roll()) > 1e-9)
		throw std::runtime_error(who +
		                         ": the bearing-range observation's sensorLocationOnRobot has a "
		                         "non-zero pitch or roll (x y z yaw pitch roll = " +
		                         p.asString() + "): 2-D SLAM needs a level sensor");
	return {p.x(), p.y(), p.yaw()};
}

estimator::TStepInput parseStepInput(const mrpt::obs::CActionCollection::Ptr& action,
                                     const mrpt::obs::CSensoryFrame::Ptr& SF,
                                     const TParseOptions& opts, const std::string& who)
{
	if (!action) throw std::runtime_error(who + ": null action collection");
	const auto mov = action->getBestMovementEstimation();
	estimator::TStepInput in;
	if (mov)
	{
		const mrpt::poses::CPosePDFGaussian inc(*mov->poseChange);
		in.u = Eigen::Vector3d(inc.mean.x(), inc.mean.y(), inc.mean.phi());
		in.U = inc.cov.asEigen();
		if (mov->timestamp != INVALID_TIMESTAMP) in.stamp = mrpt::Clock::toDouble(mov->timestamp);
	}
	else if (action->getActionByClass<mrpt::obs::CActionRobotMovement3D>())
		throw std::runtime_error(who +
		                         ": the action collection holds a CActionRobotMovement3D and no "
		                         "CActionRobotMovement2D: 2-D SLAM needs the 2-D odometry");
	else  // no odometry: CRangeBearingKFSLAM2D's u = 0, Q = diag(stds_Q_no_odo^2)
		in.U = opts.stds_Q_no_odo.cwiseAbs2().asDiagonal();
	if (!in.u.allFinite() || !in.U.allFinite())
		throw std::runtime_error(who + ": odometry increment or covariance not finite");
	if (opts.odometry_cov_used) checkOdometryCov(in.U, who);
	if (!SF) throw std::runtime_error(who + ": null sensory frame");
	const auto obs = SF->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	if (!obs)
	{
		in.boxes = readDetectionBoxes(*SF, who);
		checkBoxCorners(in.boxes, in.readings, who);  // boxes without readings: an error
		return in;
	}
	in.sensor_pose = sensorPoseOnRobot(obs->sensorLocationOnRobot, who);
	in.max_range = obs->maxSensorDistance;
	in.readings.reserve(obs->sensedData.size());
	for (size_t i = 0; i < obs->sensedData.size(); ++i)
	{
		const auto& m = obs->sensedData[i];
		// The reading named in an error (built only then: this runs for every reading).
		const auto where = [&]
		{
			return "measurement " + std::to_string(i) + " (landmark ID " +
			       std::to_string(m.landmarkID) + ")";
		};
		if (!std::isfinite(m.range) || !std::isfinite(m.yaw) || !std::isfinite(m.pitch))
			throw std::runtime_error(who + ": NaN or Inf in " + where());
		if (m.pitch != 0)
			throw std::runtime_error(who + ": non-zero pitch in " + where() + " (2-D SLAM)");
		if (!(m.range >= 0)) throw std::runtime_error(who + ": negative range in " + where());
		if (opts.model == models::MeasurementModel::RangeBearing && m.range == 0)
			throw std::runtime_error(who + ": zero range in " + where() + " (bearing undefined)");
		in.readings.push_back({m.landmarkID, models::fromRangeBearing(opts.model, m.range, m.yaw)});
	}
	readDetectionGroups(*SF, in.readings, who);  // optional hints (detection_groups.h)
	in.boxes = readDetectionBoxes(*SF, who);     // optional boxes (detection_boxes.h)
	checkBoxCorners(in.boxes, in.readings, who);
	return in;
}
}  // namespace dynslam
