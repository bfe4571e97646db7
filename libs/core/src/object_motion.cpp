#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::models
{
Eigen::VectorXd cvPredict(const Eigen::VectorXd& s, double dt, Eigen::MatrixXd* J_out_s)
{
	const Eigen::Index d = s.size() / 2;
	if (s.size() != 4 && s.size() != 6)
		throw std::invalid_argument("cvPredict: state of 4 or 6 entries, not " +
		                            std::to_string(s.size()));
	Eigen::VectorXd out = s;
	out.head(d) += dt * s.tail(d);
	if (d == 3) out[2] = wrapToPi(out[2]);
	if (J_out_s)
	{
		J_out_s->setIdentity(2 * d, 2 * d);
		J_out_s->topRightCorner(d, d).diagonal().setConstant(dt);
	}
	return out;
}

namespace
{
/** S = sin(w dt)/w, C = (1 - cos(w dt))/w and their derivatives by w; Taylor series in
 * a = w dt below 1e-2 (truncation ~ a^6, below double precision there). */
struct TTurnCoefficients
{
	double S, C, dS, dC;
};
TTurnCoefficients turnCoefficients(double w, double dt)
{
	const double a = w * dt;
	if (std::abs(a) < 1e-2)
	{
		const double a2 = a * a;
		return {dt * (1 - a2 / 6 + a2 * a2 / 120), dt * a * (0.5 - a2 / 24 + a2 * a2 / 720),
		        dt * dt * a * (-1.0 / 3 + a2 / 30), dt * dt * (0.5 - a2 / 8 + a2 * a2 / 144)};
	}
	const double s = std::sin(a), c = std::cos(a);
	return {s / w, (1 - c) / w, (dt * c * w - s) / (w * w), (dt * s * w - (1 - c)) / (w * w)};
}
}  // namespace

Eigen::VectorXd ctrvPredict(const Eigen::VectorXd& s, double dt, Eigen::MatrixXd* J_out_s)
{
	if (s.size() == 4) return cvPredict(s, dt, J_out_s);  // no turn rate without a rotation
	if (s.size() != 6)
		throw std::invalid_argument("ctrvPredict: state of 4 or 6 entries, not " +
		                            std::to_string(s.size()));
	const double w = s[5], a = w * dt;
	const TTurnCoefficients k = turnCoefficients(w, dt);
	Eigen::Matrix2d A, dA, R, dR;
	A << k.S, -k.C, k.C, k.S;
	dA << k.dS, -k.dC, k.dC, k.dS;
	R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
	dR << -std::sin(a), -std::cos(a), std::cos(a), -std::sin(a);
	dR *= dt;
	const Eigen::Vector2d v = s.segment<2>(3);
	Eigen::VectorXd out = s;
	out.head<2>() += A * v;
	out[2] = wrapToPi(s[2] + a);
	out.segment<2>(3) = R * v;
	if (J_out_s)
	{
		J_out_s->setIdentity(6, 6);
		J_out_s->block<2, 2>(0, 3) = A;
		J_out_s->block<2, 1>(0, 5) = dA * v;
		(*J_out_s)(2, 5) = dt;
		J_out_s->block<2, 2>(3, 3) = R;
		J_out_s->block<2, 1>(3, 5) = dR * v;
	}
	return out;
}

Eigen::MatrixXd cvProcessNoise(const Eigen::VectorXd& q, double dt)
{
	const Eigen::Index d = q.size();
	if ((d != 2 && d != 3) || (q.array() < 0).any() || !q.allFinite())
		throw std::invalid_argument("cvProcessNoise: 2 or 3 spectral densities >= 0");
	Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(2 * d, 2 * d);
	for (Eigen::Index i = 0; i < d; ++i)
	{
		Q(i, i) = q[i] * dt * dt * dt / 3;
		Q(i, d + i) = Q(d + i, i) = q[i] * dt * dt / 2;
		Q(d + i, d + i) = q[i] * dt;
	}
	return Q;
}

Eigen::VectorXd cvInitialVelocity(const Eigen::VectorXd& xi, double elapsed,
                                  Eigen::MatrixXd* J_v_xi)
{
	if (!(elapsed > 0)) throw std::invalid_argument("cvInitialVelocity: elapsed time must be > 0");
	if (J_v_xi) *J_v_xi = Eigen::MatrixXd::Identity(xi.size(), xi.size()) / elapsed;
	return xi / elapsed;
}

Eigen::Vector2d objectFeatureAt(const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0, int k,
                                Eigen::MatrixXd* J_f_xi, Eigen::MatrixXd* J_f_f0, int centroidCols)
{
	const Eigen::Index n = f0.cols();
	if (k < 0 || k >= n) throw std::out_of_range("objectFeatureAt: feature index");
	if (xi.size() == 2)
	{
		if (J_f_xi) *J_f_xi = Eigen::MatrixXd::Identity(2, 2);
		if (J_f_f0)
		{
			J_f_f0->setZero(2, 2 * n);
			J_f_f0->block(0, 2 * k, 2, 2).setIdentity();
		}
		return f0.col(k) + xi;
	}
	if (xi.size() != 3) throw std::invalid_argument("objectFeatureAt: pose of 2 or 3 entries");
	Eigen::MatrixXd Jxi, Jf0;
	const Eigen::Matrix2Xd ft = objectPoseMap(Eigen::Vector3d(xi), f0, J_f_xi ? &Jxi : nullptr,
	                                          J_f_f0 ? &Jf0 : nullptr, centroidCols);
	if (J_f_xi) *J_f_xi = Jxi.middleRows(2 * k, 2);
	if (J_f_f0) *J_f_f0 = Jf0.middleRows(2 * k, 2);
	return ft.col(k);
}

Eigen::Vector2d observeObjectFeature(MeasurementModel m, const Eigen::Vector3d& x,
                                     const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0, int k,
                                     Matrix23d* J_z_x, Eigen::MatrixXd* J_z_xi,
                                     Eigen::MatrixXd* J_z_f0, int centroidCols)
{
	Eigen::MatrixXd J_f_xi, J_f_f0;
	const Eigen::Vector2d f = objectFeatureAt(xi, f0, k, J_z_xi ? &J_f_xi : nullptr,
	                                          J_z_f0 ? &J_f_f0 : nullptr, centroidCols);
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector2d z = observe(m, x, f, J_z_x, &J_z_f);
	if (J_z_xi) *J_z_xi = J_z_f * J_f_xi;
	if (J_z_f0) *J_z_f0 = J_z_f * J_f_f0;
	return z;
}

Eigen::Vector2d observeObjectFeatureFromSensor(MeasurementModel m, const Eigen::Vector3d& x,
                                               const Eigen::Vector3d& s, const Eigen::VectorXd& xi,
                                               const Eigen::Matrix2Xd& f0, int k, Matrix23d* J_z_x,
                                               Eigen::MatrixXd* J_z_xi, Eigen::MatrixXd* J_z_f0,
                                               int centroidCols)
{
	Eigen::MatrixXd J_f_xi, J_f_f0;
	const Eigen::Vector2d f = objectFeatureAt(xi, f0, k, J_z_xi ? &J_f_xi : nullptr,
	                                          J_z_f0 ? &J_f_f0 : nullptr, centroidCols);
	Eigen::Matrix2d J_z_f;
	const Eigen::Vector2d z = observeFromSensor(m, x, s, f, J_z_x, &J_z_f);
	if (J_z_xi) *J_z_xi = J_z_f * J_f_xi;
	if (J_z_f0) *J_z_f0 = J_z_f * J_f_f0;
	return z;
}
}  // namespace dynslam::models
