#pragma once
/** @file step_input.h
 * The one step-input parser of every back-end (the EKF and the framework's): the odometry
 * increment of the CActionRobotMovement2D and the readings of the first
 * CObservationBearingRange, checked and expressed in the model's measurement space. What each
 * reading is (static, object feature, ...) is the measurement router's business
 * (dynslam/estimator/measurement_router.h), which validates the IDs. Throws
 * std::runtime_error, prefixed by `who`, before anything is changed. The sensor's pose on the
 * robot (sensorLocationOnRobot, see sensorPoseOnRobot) goes to TStepInput::sensor_pose. A step
 * without odometry is taken as MRPT takes it (TParseOptions::stds_Q_no_odo). Optional:
 * the readings' detection groups (DETECTION_GROUPS comment, detection_groups.h) and the
 * detector boxes (DETECTION_BOXES comment, detection_boxes.h: TStepInput::boxes, each box's
 * group checked to be the hint of exactly its four ID -1 corner readings). Readings with ID -1
 * are passed on as they are (the router decides what they are). */
#include <dynslam/core/models/measurement.h>
#include <dynslam/estimator/readings.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <string>

namespace dynslam
{
struct TParseOptions
{
	models::MeasurementModel model = models::MeasurementModel::Cartesian;
	/** The action's covariance is the motion noise (motion_noise = action): it must then be
	 * symmetric positive semi-definite. */
	bool odometry_cov_used = true;
	/** A step whose action collection holds no CActionRobotMovement2D (no odometry): u = 0 and
	 * U = diag(stds_Q_no_odo^2), as CRangeBearingKFSLAM2D::OnTransitionNoise does with its
	 * option of that name (x [m], y [m], phi [rad]; MRPT's default 0.10 m, 0.10 m, 4 deg). */
	Eigen::Vector3d stds_Q_no_odo = Eigen::Vector3d(0.10, 0.10, 4.0 * M_PI / 180.0);
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
