#pragma once
/** @file rawlog_writer.h
 * Writes an import (import.h) as an MRPT rawlog, format #1: pairs (CActionCollection,
 * CSensoryFrame), one per step, gz-compressed as MRPT writes it.
 *  - The action holds one CActionRobotMovement2D: poseChange = CPosePDFGaussian(increment,
 *    covariance of TOdometryNoiseModel), rawOdometryIncrementReading = increment,
 *    timestamp = step time. Step 0: zero increment, zero cov. estimationMethod is
 *    emScan2DMatching, not emOdometry: MRPT stores an emOdometry action as the raw increment
 *    plus its own motion-model parameters and rebuilds the covariance from them when reading
 *    (CActionRobotMovement2D::serializeFrom), which would replace this noise model; with any
 *    other method the Gaussian itself is stored. Readers (CRangeBearingKFSLAM2D, the dynamic
 *    EKF) only use poseChange.
 *  - The sensory frame holds one CObservationBearingRange: sensorLabel "RB", timestamp = step
 *    time (from the data), maxSensorDistance = max_range, minSensorDistance = 0,
 *    fieldOfView_yaw = 2 pi, fieldOfView_pitch = 0, sensor at the robot origin,
 *    sensor_std_range / sensor_std_yaw = std_range / std_bearing, validCovariances = false;
 *    one TMeasurement per kept measurement (range, yaw = bearing, pitch = 0, landmarkID).
 * Plus the companion files `<base>_summary.txt`, `<base>_import.ini` and the class ground truth
 * `<base>_gt_classes.csv` (anonymous.h). */
#include <dynslam/mrclam/CMrclamOptions.h>
#include <dynslam/mrclam/import.h>

#include <string>

namespace dynslam::mrclam
{
/** Writes `path` (the rawlog). Throws std::runtime_error if the file cannot be written. */
void writeRawlog(const TImportResult& res, const TImportOptions& opts, const std::string& path);

/** Writes into `dir` (created if missing): `<base>.rawlog`, the ground truth
 * (dynslam::io::writeGroundTruth, files `<base>_gt_*`), `<base>_gt_classes.csv` (anonymous.h),
 * `<base>_summary.txt` and
 * `<base>_import.ini` (effective options, the world origin, and the filter start
 * [DynamicKFSLAM] initial_pose / Sigma_0). */
void writeImport(const TImportResult& res, const TMrclamOptions& opts, const std::string& dir,
                 const std::string& base);
}  // namespace dynslam::mrclam
