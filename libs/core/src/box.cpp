#include <dynslam/core/models/box.h>
#include <dynslam/core/models/se2.h>

#include <cmath>

namespace dynslam::models
{
Vector5d boxObserve(const Eigen::Vector3d& x, const Eigen::Vector3d& o, const Eigen::Vector2d& e,
                    Matrix53d* J_z_x, Matrix53d* J_z_o, Matrix52d* J_z_e)
{
	const Eigen::Matrix2d Rt = rot2(x.z()).transpose();
	const Eigen::Vector2d d = o.head<2>() - x.head<2>();
	Vector5d z;
	z << Rt * d, wrapToPi(o.z() - x.z()), e;
	if (J_z_x)
	{
		J_z_x->setZero();
		J_z_x->block<2, 2>(0, 0) = -Rt;
		J_z_x->block<2, 1>(0, 2) = rot2Derivative(x.z()).transpose() * d;
		(*J_z_x)(2, 2) = -1;
	}
	if (J_z_o)
	{
		J_z_o->setZero();
		J_z_o->block<2, 2>(0, 0) = Rt;
		(*J_z_o)(2, 2) = 1;
	}
	if (J_z_e)
	{
		J_z_e->setZero();
		J_z_e->block<2, 2>(3, 0).setIdentity();
	}
	return z;
}

Eigen::Vector3d boxInverse(const Eigen::Vector3d& x, const Vector5d& z, Eigen::Matrix3d* J_o_x,
                           Eigen::Matrix<double, 3, 5>* J_o_z)
{
	const Eigen::Matrix2d R = rot2(x.z());
	const Eigen::Vector2d c = z.head<2>();
	Eigen::Vector3d o;
	o << x.head<2>() + R * c, wrapToPi(x.z() + z(2));
	if (J_o_x)
	{
		J_o_x->setIdentity();
		J_o_x->block<2, 1>(0, 2) = rot2Derivative(x.z()) * c;
	}
	if (J_o_z)
	{
		J_o_z->setZero();
		J_o_z->block<2, 2>(0, 0) = R;
		(*J_o_z)(2, 2) = 1;
	}
	return o;
}

Vector5d boxInnovation(const Vector5d& z, const Vector5d& zhat, bool* flipped)
{
	Vector5d r = z - zhat;
	double a = wrapToPi(r(2));
	const bool flip = a > M_PI / 2 || a <= -M_PI / 2;
	if (flip) a = wrapToPi(a - M_PI);
	r(2) = a;
	if (flipped) *flipped = flip;
	return r;
}
}  // namespace dynslam::models
