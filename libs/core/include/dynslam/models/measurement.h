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
Eigen::Vector2d cartesianObserve(
	const Eigen::Vector3d& x, const Eigen::Vector2d& f, Matrix23d* J_z_x = nullptr,
	Eigen::Matrix2d* J_z_f = nullptr);
Eigen::Vector2d cartesianInverse(
	const Eigen::Vector3d& x, const Eigen::Vector2d& z, Matrix23d* J_f_x = nullptr,
	Eigen::Matrix2d* J_f_z = nullptr);

// --- Range-bearing -------------------------------------------------------------
/** z = (range, bearing), bearing wrapped to (-pi, pi]. Throws std::domain_error when f
 * coincides with the sensor (range 0: bearing and Jacobians undefined). */
Eigen::Vector2d rangeBearingObserve(
	const Eigen::Vector3d& x, const Eigen::Vector2d& f, Matrix23d* J_z_x = nullptr,
	Eigen::Matrix2d* J_z_f = nullptr);
Eigen::Vector2d rangeBearingInverse(
	const Eigen::Vector3d& x, const Eigen::Vector2d& z, Matrix23d* J_f_x = nullptr,
	Eigen::Matrix2d* J_f_z = nullptr);

// --- Conversions between the two measurement spaces ----------------------------
/** (range, bearing) -> Cartesian sensor-frame point, with J_c_rb (2x2). */
Eigen::Vector2d rangeBearingToCartesian(const Eigen::Vector2d& rb, Eigen::Matrix2d* J_c_rb = nullptr);
/** Cartesian sensor-frame point -> (range, bearing), with J_rb_c (2x2). */
Eigen::Vector2d cartesianToRangeBearing(const Eigen::Vector2d& c, Eigen::Matrix2d* J_rb_c = nullptr);

// --- Dispatch on the selected model ---------------------------------------------
Eigen::Vector2d observe(
	MeasurementModel m, const Eigen::Vector3d& x, const Eigen::Vector2d& f,
	Matrix23d* J_z_x = nullptr, Eigen::Matrix2d* J_z_f = nullptr);
Eigen::Vector2d inverseObserve(
	MeasurementModel m, const Eigen::Vector3d& x, const Eigen::Vector2d& z,
	Matrix23d* J_f_x = nullptr, Eigen::Matrix2d* J_f_z = nullptr);
/** A stored (range, bearing) reading expressed in the model's measurement space. */
Eigen::Vector2d fromRangeBearing(MeasurementModel m, double range, double bearing);
/** Innovation z - zhat, bearing component wrapped for the range-bearing model. */
Eigen::Vector2d innovation(MeasurementModel m, const Eigen::Vector2d& z, const Eigen::Vector2d& zhat);
}  // namespace dynslam::models
