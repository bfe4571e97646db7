#pragma once
/** @file step_input.h
 * One step's input, parsed and validated as CDynamicKFSLAM2D does: the odometry increment of
 * the CActionRobotMovement2D and the measurements of the first CObservationBearingRange,
 * split into static landmarks and object features by ID (dynslam/landmark_ids.h) and
 * expressed in the model's measurement space. Throws std::runtime_error on bad input. */
#include <dynslam/models/measurement.h>

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace dynslam::framework
{
struct TMeasurement
{
	int32_t id;
	Eigen::Vector2d z;
};

struct TStepInput
{
	Eigen::Vector3d u = Eigen::Vector3d::Zero();  ///< odometry increment (robot frame)
	Eigen::Matrix3d U = Eigen::Matrix3d::Zero();  ///< its covariance (from the action)
	std::vector<TMeasurement> statics, objects;
	double max_range = 0;
};

TStepInput parseStepInput(
	const mrpt::obs::CActionCollection::Ptr& action, const mrpt::obs::CSensoryFrame::Ptr& SF,
	models::MeasurementModel model, const char* who);
}  // namespace dynslam::framework
