#pragma once
/** @file readings.h
 * One step's input after parsing, independent of MRPT: the odometry increment and the
 * readings of the step in the measurement model's space. Produced by the one step-input
 * parser (dynslam/common/step_input.h, libs/common), consumed by every back-end through an
 * IMeasurementRouter. */
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace dynslam::estimator
{
/** One reading: the landmark / track ID it carries and z in the model's measurement space. */
struct TReading
{
	int32_t id;
	Eigen::Vector2d z;
	/** Optional detection group (a box / detection ID of the front-end) of this reading, -1:
	 * none. Read from the step's DETECTION_GROUPS comment (dynslam/common/detection_groups.h); used
	 * only by the classifying router with classify_use_hints (doc/results/classification.md,
	 * "Hints").
	 */
	int32_t hint = -1;
};

/** One box of a 3-D detector in the bird's-eye view (issue 31; the rawlog's DETECTION_BOXES
 * comment, dynslam/common/detection_boxes.h): no track ID. Its four footprint corners are also
 * readings of the step (ID -1, hint = group), in the order front-left, front-right, rear-right,
 * rear-left of the box frame (x along the heading, y to its left). */
struct TBoxDetection
{
	int32_t group = -1;  ///< the detection group of its four corner readings (TReading::hint)
	std::string cls;     ///< the detector's class, e.g. "Car"
	double score = 0;    ///< the detector's confidence (no range imposed)
	/** Centre (x, y) [m] and heading yaw [rad] of the length axis, in the sensor frame; a
	 * detector cannot tell the front from the back (yaw and yaw + pi: the same footprint). */
	Eigen::Vector3d pose = Eigen::Vector3d::Zero();
	Eigen::Vector2d extent = Eigen::Vector2d::Zero();  ///< (length, width) [m], > 0
};

struct TStepInput
{
	Eigen::Vector3d u = Eigen::Vector3d::Zero();  ///< odometry increment (robot frame)
	Eigen::Matrix3d U = Eigen::Matrix3d::Zero();  ///< its covariance (from the action)
	std::vector<TReading> readings;               ///< in observation order, IDs unique
	double max_range = 0;                         ///< the sensor's range [m] (0: unknown)
	/** The action's timestamp [s] (NaN: none); gives the step's dt to the odometry bias. */
	double stamp = std::numeric_limits<double>::quiet_NaN();
	/** The sensor's pose on the robot s = (x, y, yaw) (the SE(2) part of MRPT's
	 * sensorLocationOnRobot): every reading of the step is z = h(x (+) s, f)
	 * (dynslam/core/models/measurement.h, observeFromSensor). Zero: the sensor at the origin. */
	Eigen::Vector3d sensor_pose = Eigen::Vector3d::Zero();
	/** The step's detector boxes (DETECTION_BOXES comment; empty without one). */
	std::vector<TBoxDetection> boxes;
};
}  // namespace dynslam::estimator
