#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::models
{
std::string toString(MeasurementModel m)
{
	return m == MeasurementModel::Cartesian ? "cartesian" : "range_bearing";
}

MeasurementModel measurementModelFromString(const std::string& s)
{
	std::string l = s;
	std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return std::tolower(c); });
	if (l == "cartesian") return MeasurementModel::Cartesian;
	if (l == "range_bearing" || l == "rangebearing") return MeasurementModel::RangeBearing;
	throw std::invalid_argument("unknown measurement model '" + s +
	                            "' (expected cartesian or range_bearing)");
}

Eigen::Vector2d cartesianObserve(const Eigen::Vector3d& x, const Eigen::Vector2d& f,
                                 Matrix23d* J_z_x, Eigen::Matrix2d* J_z_f)
{
	const Eigen::Matrix2d Rt = rot2(x[2]).transpose();
	const Eigen::Vector2d d = f - x.head<2>();
	if (J_z_x)
	{
		J_z_x->leftCols<2>() = -Rt;
		J_z_x->col(2) = rot2Derivative(x[2]).transpose() * d;
	}
	if (J_z_f) *J_z_f = Rt;
	return Rt * d;
}

Eigen::Vector2d cartesianInverse(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                 Matrix23d* J_f_x, Eigen::Matrix2d* J_f_z)
{
	const Eigen::Matrix2d R = rot2(x[2]);
	if (J_f_x)
	{
		J_f_x->leftCols<2>().setIdentity();
		J_f_x->col(2) = rot2Derivative(x[2]) * z;
	}
	if (J_f_z) *J_f_z = R;
	return x.head<2>() + R * z;
}

Eigen::Vector2d rangeBearingObserve(const Eigen::Vector3d& x, const Eigen::Vector2d& f,
                                    Matrix23d* J_z_x, Eigen::Matrix2d* J_z_f)
{
	const Eigen::Vector2d d = f - x.head<2>();
	const double r2 = d.squaredNorm();
	if (!(r2 > 0))
		throw std::domain_error("rangeBearingObserve: feature coincides with the sensor");
	const double r = std::sqrt(r2);
	if (J_z_f) *J_z_f << d[0] / r, d[1] / r, -d[1] / r2, d[0] / r2;
	if (J_z_x) *J_z_x << -d[0] / r, -d[1] / r, 0, d[1] / r2, -d[0] / r2, -1;
	return {r, wrapToPi(std::atan2(d[1], d[0]) - x[2])};
}

Eigen::Vector2d rangeBearingInverse(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                    Matrix23d* J_f_x, Eigen::Matrix2d* J_f_z)
{
	const double a = x[2] + z[1], c = std::cos(a), s = std::sin(a);
	if (J_f_x) *J_f_x << 1, 0, -z[0] * s, 0, 1, z[0] * c;
	if (J_f_z) *J_f_z << c, -z[0] * s, s, z[0] * c;
	return {x[0] + z[0] * c, x[1] + z[0] * s};
}

Eigen::Vector2d rangeBearingToCartesian(const Eigen::Vector2d& rb, Eigen::Matrix2d* J_c_rb)
{
	const double c = std::cos(rb[1]), s = std::sin(rb[1]);
	if (J_c_rb) *J_c_rb << c, -rb[0] * s, s, rb[0] * c;
	return {rb[0] * c, rb[0] * s};
}

Eigen::Vector2d cartesianToRangeBearing(const Eigen::Vector2d& c, Eigen::Matrix2d* J_rb_c)
{
	const double r2 = c.squaredNorm();
	if (!(r2 > 0)) throw std::domain_error("cartesianToRangeBearing: point at the sensor origin");
	const double r = std::sqrt(r2);
	if (J_rb_c) *J_rb_c << c[0] / r, c[1] / r, -c[1] / r2, c[0] / r2;
	return {r, wrapToPi(std::atan2(c[1], c[0]))};  // atan2 may return -pi
}

Eigen::Vector2d observe(MeasurementModel m, const Eigen::Vector3d& x, const Eigen::Vector2d& f,
                        Matrix23d* J_z_x, Eigen::Matrix2d* J_z_f)
{
	return m == MeasurementModel::Cartesian ? cartesianObserve(x, f, J_z_x, J_z_f)
	                                        : rangeBearingObserve(x, f, J_z_x, J_z_f);
}

Eigen::Vector2d inverseObserve(MeasurementModel m, const Eigen::Vector3d& x,
                               const Eigen::Vector2d& z, Matrix23d* J_f_x, Eigen::Matrix2d* J_f_z)
{
	return m == MeasurementModel::Cartesian ? cartesianInverse(x, z, J_f_x, J_f_z)
	                                        : rangeBearingInverse(x, z, J_f_x, J_f_z);
}

Eigen::Vector2d fromRangeBearing(MeasurementModel m, double range, double bearing)
{
	const Eigen::Vector2d rb(range, bearing);
	return m == MeasurementModel::Cartesian ? rangeBearingToCartesian(rb) : rb;
}

Eigen::Vector2d innovation(MeasurementModel m, const Eigen::Vector2d& z,
                           const Eigen::Vector2d& zhat)
{
	Eigen::Vector2d d = z - zhat;
	if (m == MeasurementModel::RangeBearing) d[1] = wrapToPi(d[1]);
	return d;
}
// ------------------------------------------------------------------------------------------
// Sensor not at the robot's origin: z = h(x (+) s, f), f = l(x (+) s, z), chain rule through
// the sensor's world pose xs = x (+) s.
// ------------------------------------------------------------------------------------------
namespace
{
void requireFiniteSensorPose(const Eigen::Vector3d& s)
{
	if (!s.allFinite())
		throw std::invalid_argument("sensor pose on the robot (x_s, y_s, yaw_s) = (" +
		                            std::to_string(s[0]) + ", " + std::to_string(s[1]) + ", " +
		                            std::to_string(s[2]) + ") is not finite");
}

/** J_out_x = J_out_xs * J_xs_x and J_out_s = J_out_xs * J_xs_s for a model evaluated at xs. */
template <typename Model>
Eigen::Vector2d throughSensor(const Model& model, const Eigen::Vector3d& x,
                              const Eigen::Vector3d& s, const Eigen::Vector2d& in,
                              Matrix23d* J_out_x, Eigen::Matrix2d* J_out_in, Matrix23d* J_out_s)
{
	requireFiniteSensorPose(s);
	Eigen::Matrix3d J_xs_x, J_xs_s;
	const bool chain = J_out_x || J_out_s;
	const Eigen::Vector3d xs =
	    sensorPoseInWorld(x, s, chain ? &J_xs_x : nullptr, chain ? &J_xs_s : nullptr);
	Matrix23d J_out_xs;
	const Eigen::Vector2d out = model(xs, in, chain ? &J_out_xs : nullptr, J_out_in);
	if (J_out_x) *J_out_x = J_out_xs * J_xs_x;
	if (J_out_s) *J_out_s = J_out_xs * J_xs_s;
	return out;
}
}  // namespace

Eigen::Vector3d sensorPoseInWorld(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                  Eigen::Matrix3d* J_xs_x, Eigen::Matrix3d* J_xs_s)
{
	requireFiniteSensorPose(s);
	const double c = std::cos(x[2]), sn = std::sin(x[2]);
	// Not wrapped: x[2] + 0 == x[2], so s = 0 reproduces the sensor-at-origin models exactly.
	const Eigen::Vector3d xs(x[0] + c * s[0] - sn * s[1], x[1] + sn * s[0] + c * s[1], x[2] + s[2]);
	if (J_xs_x) *J_xs_x << 1, 0, -sn * s[0] - c * s[1], 0, 1, c * s[0] - sn * s[1], 0, 0, 1;
	if (J_xs_s) *J_xs_s << c, -sn, 0, sn, c, 0, 0, 0, 1;
	return xs;
}

Eigen::Vector2d cartesianObserveFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                           const Eigen::Vector2d& f, Matrix23d* J_z_x,
                                           Eigen::Matrix2d* J_z_f, Matrix23d* J_z_s)
{
	return throughSensor([](const Eigen::Vector3d& p, const Eigen::Vector2d& v, Matrix23d* Jp,
	                        Eigen::Matrix2d* Jv) { return cartesianObserve(p, v, Jp, Jv); },
	                     x, s, f, J_z_x, J_z_f, J_z_s);
}

Eigen::Vector2d cartesianInverseFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                           const Eigen::Vector2d& z, Matrix23d* J_f_x,
                                           Eigen::Matrix2d* J_f_z, Matrix23d* J_f_s)
{
	return throughSensor([](const Eigen::Vector3d& p, const Eigen::Vector2d& v, Matrix23d* Jp,
	                        Eigen::Matrix2d* Jv) { return cartesianInverse(p, v, Jp, Jv); },
	                     x, s, z, J_f_x, J_f_z, J_f_s);
}

Eigen::Vector2d rangeBearingObserveFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                              const Eigen::Vector2d& f, Matrix23d* J_z_x,
                                              Eigen::Matrix2d* J_z_f, Matrix23d* J_z_s)
{
	return throughSensor([](const Eigen::Vector3d& p, const Eigen::Vector2d& v, Matrix23d* Jp,
	                        Eigen::Matrix2d* Jv) { return rangeBearingObserve(p, v, Jp, Jv); },
	                     x, s, f, J_z_x, J_z_f, J_z_s);
}

Eigen::Vector2d rangeBearingInverseFromSensor(const Eigen::Vector3d& x, const Eigen::Vector3d& s,
                                              const Eigen::Vector2d& z, Matrix23d* J_f_x,
                                              Eigen::Matrix2d* J_f_z, Matrix23d* J_f_s)
{
	return throughSensor([](const Eigen::Vector3d& p, const Eigen::Vector2d& v, Matrix23d* Jp,
	                        Eigen::Matrix2d* Jv) { return rangeBearingInverse(p, v, Jp, Jv); },
	                     x, s, z, J_f_x, J_f_z, J_f_s);
}

Eigen::Vector2d observeFromSensor(MeasurementModel m, const Eigen::Vector3d& x,
                                  const Eigen::Vector3d& s, const Eigen::Vector2d& f,
                                  Matrix23d* J_z_x, Eigen::Matrix2d* J_z_f, Matrix23d* J_z_s)
{
	return m == MeasurementModel::Cartesian
	           ? cartesianObserveFromSensor(x, s, f, J_z_x, J_z_f, J_z_s)
	           : rangeBearingObserveFromSensor(x, s, f, J_z_x, J_z_f, J_z_s);
}

Eigen::Vector2d inverseObserveFromSensor(MeasurementModel m, const Eigen::Vector3d& x,
                                         const Eigen::Vector3d& s, const Eigen::Vector2d& z,
                                         Matrix23d* J_f_x, Eigen::Matrix2d* J_f_z, Matrix23d* J_f_s)
{
	return m == MeasurementModel::Cartesian
	           ? cartesianInverseFromSensor(x, s, z, J_f_x, J_f_z, J_f_s)
	           : rangeBearingInverseFromSensor(x, s, z, J_f_x, J_f_z, J_f_s);
}
}  // namespace dynslam::models
