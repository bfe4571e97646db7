#include <dynslam/core/models/se2.h>

#include <cmath>

namespace dynslam::models
{
double wrapToPi(double a)
{
	if (a > -M_PI && a <= M_PI) return a;
	a = std::fmod(a + M_PI, 2 * M_PI);
	if (a <= 0) a += 2 * M_PI;
	return a - M_PI;
}

Eigen::Matrix2d rot2(double theta)
{
	const double c = std::cos(theta), s = std::sin(theta);
	Eigen::Matrix2d R;
	R << c, -s, s, c;
	return R;
}

Eigen::Matrix2d rot2Derivative(double theta)
{
	const double c = std::cos(theta), s = std::sin(theta);
	Eigen::Matrix2d D;
	D << -s, -c, c, -s;
	return D;
}

Eigen::Vector3d composePose(const Eigen::Vector3d& x, const Eigen::Vector3d& u,
                            Eigen::Matrix3d* J_out_x, Eigen::Matrix3d* J_out_u)
{
	const double c = std::cos(x[2]), s = std::sin(x[2]);
	Eigen::Vector3d out;
	out[0] = x[0] + c * u[0] - s * u[1];
	out[1] = x[1] + s * u[0] + c * u[1];
	out[2] = wrapToPi(x[2] + u[2]);
	if (J_out_x)
	{
		*J_out_x << 1, 0, -s * u[0] - c * u[1],  //
		    0, 1, c * u[0] - s * u[1],           //
		    0, 0, 1;
	}
	if (J_out_u)
	{
		*J_out_u << c, -s, 0,  //
		    s, c, 0,           //
		    0, 0, 1;
	}
	return out;
}

Eigen::Vector3d poseDifference(const Eigen::Vector3d& b, const Eigen::Vector3d& a)
{
	const Eigen::Vector2d d = rot2(a[2]).transpose() * (b.head<2>() - a.head<2>());
	return {d[0], d[1], wrapToPi(b[2] - a[2])};
}
}  // namespace dynslam::models
