#pragma once
/** @file step_input.h
 * The one step-input parser of every back-end (the EKF and the framework's): the odometry
 * increment of the CActionRobotMovement2D and the readings of the first
 * CObservationBearingRange, checked and expressed in the model's measurement space. What each
 * reading is (static, object feature, ...) is the measurement router's business
 * (dynslam/estimator/measurement_router.h), which validates the IDs. Throws
 * std::runtime_error, prefixed by `who`, before anything is changed. The sensor's pose on the
 * robot (sensorLocationOnRobot, see sensorPoseOnRobot) goes to TStepInput::sensor_pose. */
#include <dynslam/estimator/readings.h>
#include <dynslam/models/measurement.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>

#include <string>

namespace dynslam
{
struct TParseOptions
{
	models::MeasurementModel model = models::MeasurementModel::Cartesian;
	/** The action's covariance is the motion noise (motion_noise = action): it must then be
	 * symmetric positive semi-definite. */
	bool odometry_cov_used = true;
};

/** The SE(2) pose (x, y, yaw) of a sensor on the robot from MRPT's sensorLocationOnRobot.
 * Throws std::runtime_error (prefixed by `who`) if a component is not finite, or if pitch or
 * roll exceeds 1e-9 rad (2-D SLAM: a tilted sensor does not measure bearings in the map's plane).
 * The height z is ignored, as CRangeBearingKFSLAM2D does: with pitch 0 the readings are in the
 * sensor's horizontal plane. */
Eigen::Vector3d sensorPoseOnRobot(const mrpt::poses::CPose3D& p, const std::string& who);

estimator::TStepInput parseStepInput(const mrpt::obs::CActionCollection::Ptr& action,
                                     const mrpt::obs::CSensoryFrame::Ptr& SF,
                                     const TParseOptions& opts, const std::string& who);
}  // namespace dynslam
