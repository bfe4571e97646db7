#pragma once
/** @file measurement.h
 * Measurement models z = h(x, f) of a 2-D point feature f seen from the ego pose
 * x = (x, y, theta), their inverses f = l(x, z) (paper Alg. 3, Appendix C), and
 * analytic Jacobians.
 *
 * - Cartesian (paper, Appendix C): z = R(theta)^T (f - p), noise Sigma_v on z.
 * - Range-bearing (MRPT's CRangeBearingKFSLAM2D): z = (|f - p|, atan2(f - p) - theta).
 *
 * Rawlogs always store range and bearing (CObservationBearingRange); fromRangeBearing()
 * converts them exactly into the selected model's measurement space. */
#include <Eigen/Core>
#include <string>

namespace dynslam::models
{
enum class MeasurementModel
{
	Cartesian,
	RangeBearing
};

std::string toString(MeasurementModel m);
/** Parses "cartesian" / "range_bearing" (case-insensitive); throws std::invalid_argument. */
MeasurementModel measurementModelFromString(const std::string& s);

using Matrix23d = Eigen::Matrix<double, 2, 3>;

// --- Cartesian ---------------------------------------------------------------
Eigen::Vector2d cartesianObserve(const Eigen::Vector3d& x, const Eigen::Vector2d& f,
                                 Matrix23d* J_z_x = nullptr, Eigen::Matrix2d* J_z_f = nullptr);
Eigen::Vector2d cartesianInverse(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                 Matrix23d* J_f_x = nullptr, Eigen::Matrix2d* J_f_z = nullptr);

// --- Range-bearing -------------------------------------------------------------
/** z = (range, bearing), bearing wrapped to (-pi, pi]. Throws std::domain_error when f
 * coincides with the sensor (range 0: bearing and Jacobians undefined). */
Eigen::Vector2d rangeBearingObserve(const Eigen::Vector3d& x, const Eigen::Vector2d& f,
                                    Matrix23d* J_z_x = nullptr, Eigen::Matrix2d* J_z_f = nullptr);
Eigen::Vector2d rangeBearingInverse(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                    Matrix23d* J_f_x = nullptr, Eigen::Matrix2d* J_f_z = nullptr);

// --- Conversions between the two measurement spaces ----------------------------
/** (range, bearing) -> Cartesian sensor-frame point, with J_c_rb (2x2). */
Eigen::Vector2d rangeBearingToCartesian(const Eigen::Vector2d& rb,
                                        Eigen::Matrix2d* J_c_rb = nullptr);
/** Cartesian sensor-frame point -> (range, bearing), with J_rb_c (2x2). */
Eigen::Vector2d cartesianToRangeBearing(const Eigen::Vector2d& c,
                                        Eigen::Matrix2d* J_rb_c = nullptr);

// --- Dispatch on the selected model ---------------------------------------------
Eigen::Vector2d observe(MeasurementModel m, const Eigen::Vector3d& x, const Eigen::Vector2d& f,
                        Matrix23d* J_z_x = nullptr, Eigen::Matrix2d* J_z_f = nullptr);
Eigen::Vector2d inverseObserve(MeasurementModel m, const Eigen::Vector3d& x,
                               const Eigen::Vector2d& z, Matrix23d* J_f_x = nullptr,
                               Eigen::Matrix2d* J_f_z = nullptr);
// --- Sensor not at the robot's origin ----------------------------------------------
// The sensor sits at s = (x_s, y_s, yaw_s) in the robot frame (the SE(2) part of MRPT's
// CObservationBearingRange::sensorLocationOnRobot). A reading is taken from the sensor's
// pose x (+) s, as in MRPT's CRangeBearingKFSLAM2D: z = h(x (+) s, f) and f = l(x (+) s, z).
// Jacobians w.r.t. the ego x, the feature f / the measurement z, and the sensor pose s.
// s = (0, 0, 0) reproduces the functions above bit for bit. A non-finite s throws
// std::invalid_argument.

/** The sensor's pose in the world, x (+) s, with its heading NOT wrapped (so that s = 0 gives
 * x exactly; the models only use its cosine and sine). J_xs_x, J_xs_s: 3x3. */
Eigen::Vector3d sensorPoseInWorld(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                  Eigen::Matrix3d* J_xs_x = nullptr,
                                  Eigen::Matrix3d* J_xs_s = nullptr);

Eigen::Vector2d cartesianObserveFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                           const Eigen::Vector2d& f, Matrix23d* J_z_x = nullptr,
                                           Eigen::Matrix2d* J_z_f = nullptr,
                                           Matrix23d* J_z_s = nullptr);
Eigen::Vector2d cartesianInverseFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                           const Eigen::Vector2d& z, Matrix23d* J_f_x = nullptr,
                                           Eigen::Matrix2d* J_f_z = nullptr,
                                           Matrix23d* J_f_s = nullptr);
/** Throws std::domain_error when f coincides with the sensor. */
Eigen::Vector2d rangeBearingObserveFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                              const Eigen::Vector2d& f, Matrix23d* J_z_x = nullptr,
                                              Eigen::Matrix2d* J_z_f = nullptr,
                                              Matrix23d* J_z_s = nullptr);
Eigen::Vector2d rangeBearingInverseFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                              const Eigen::Vector2d& z, Matrix23d* J_f_x = nullptr,
                                              Eigen::Matrix2d* J_f_z = nullptr,
                                              Matrix23d* J_f_s = nullptr);
/** Dispatch on the model. */
Eigen::Vector2d observeFromSensor(MeasurementModel m, const Eigen::Vector3d& x,
                                  const Eigen::Vector3d& s, const Eigen::Vector2d& f,
                                  Matrix23d* J_z_x = nullptr, Eigen::Matrix2d* J_z_f = nullptr,
                                  Matrix23d* J_z_s = nullptr);
Eigen::Vector2d inverseObserveFromSensor(MeasurementModel m, const Eigen::Vector3d& x,
                                         const Eigen::Vector3d& s, const Eigen::Vector2d& z,
                                         Matrix23d* J_f_x = nullptr,
                                         Eigen::Matrix2d* J_f_z = nullptr,
                                         Matrix23d* J_f_s = nullptr);

/** A stored (range, bearing) reading expressed in the model's measurement space. */
Eigen::Vector2d fromRangeBearing(MeasurementModel m, double range, double bearing);
/** Innovation z - zhat, bearing component wrapped for the range-bearing model. */
Eigen::Vector2d innovation(MeasurementModel m, const Eigen::Vector2d& z,
                           const Eigen::Vector2d& zhat);
}  // namespace dynslam::models
