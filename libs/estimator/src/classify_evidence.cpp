/** The statistics of the classifying router (classify_evidence.h). */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/classify_evidence.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace dynslam::estimator
{
TPoint2 readingInRobotFrame(const TRouterContext& ctx, const Eigen::Vector2d& z)
{
	Eigen::Matrix2d J_q_z;
	TPoint2 out;
	out.p = models::inverseObserveFromSensor(ctx.model, Eigen::Vector3d::Zero(), ctx.sensor_pose, z,
	                                         nullptr, &J_q_z);
	out.C = J_q_z * ctx.R * J_q_z.transpose();
	return out;
}

TStaticMotion::TStaticMotion(const Eigen::Vector3d& u_, const Eigen::Matrix3d& U_)
    : u(u_),
      U(U_),
      Rt(models::rot2(u_[2]).transpose()),
      dRt(models::rot2Derivative(u_[2]).transpose())
{
}

TPoint2 predictStatic(const TPoint2& q, const TStaticMotion& m)
{
	const Eigen::Matrix2d& Rt = m.Rt;
	const Eigen::Vector2d d = q.p - m.u.head<2>();
	Eigen::Matrix<double, 2, 3> J_u;
	J_u.leftCols<2>() = -Rt;
	J_u.col(2) = m.dRt * d;
	TPoint2 out;
	out.p = Rt * d;
	out.C = Rt * q.C * Rt.transpose() + J_u * m.U * J_u.transpose();
	return out;
}

TPoint2 predictStatic(const TPoint2& q, const Eigen::Vector3d& u, const Eigen::Matrix3d& U)
{
	return predictStatic(q, TStaticMotion(u, U));
}

namespace
{
double logGauss0(const Eigen::Vector2d& nu, const Eigen::Matrix2d& S)
{
	const Eigen::LLT<Eigen::Matrix2d> llt(S);
	if (llt.info() != Eigen::Success)
		throw std::runtime_error("movingLogLikelihoodRatio: covariance not positive definite");
	const Eigen::Vector2d w = llt.matrixL().solve(nu);
	const double logdet = 2 * std::log(llt.matrixL()(0, 0) * llt.matrixL()(1, 1));
	return -0.5 * (w.squaredNorm() + logdet);
}
}  // namespace

double movingLogLikelihoodRatio(const Eigen::Vector2d& nu, const Eigen::Matrix2d& S,
                                const Eigen::Matrix2d& Q)
{
	return logGauss0(nu, S + Q) - logGauss0(nu, S);
}

namespace
{
/** Standard normal quantile by bisection on the CDF (|error| < 1e-12). */
double normalQuantile(double p)
{
	double lo = -40, hi = 40;
	for (int i = 0; i < 200; ++i)
	{
		const double mid = 0.5 * (lo + hi);
		(0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
	}
	return 0.5 * (lo + hi);
}

/** normalQuantile with the last few probabilities remembered (per thread): the router asks for
 * the same two or three (classify_group_prob, classify_reclassify_gate) many times per step, and
 * the 200 bisection steps on erfc were a third of a classifying highway run
 * (doc/results/performance.md 14). The same values, bit for bit. */
double normalQuantileCached(double p)
{
	constexpr int kSlots = 4;
	thread_local double keys[kSlots] = {-1, -1, -1, -1}, values[kSlots] = {0, 0, 0, 0};
	thread_local int next = 0;
	for (int i = 0; i < kSlots; ++i)
		if (keys[i] == p) return values[i];
	const double z = normalQuantile(p);
	keys[next] = p;
	values[next] = z;
	next = (next + 1) % kSlots;
	return z;
}
}  // namespace

double chiSquareQuantile(double p, int dof)
{
	if (!(p > 0 && p < 1) || dof < 1)
		throw std::invalid_argument("chiSquareQuantile: need p in (0, 1) and dof >= 1");
	if (dof == 2) return -2 * std::log(1 - p);
	const double k = dof, z = normalQuantileCached(p), c = 2 / (9 * k);
	const double t = 1 - c + z * std::sqrt(c);
	return k * t * t * t;
}

namespace
{
/** The distance of two points and its variance along their direction. */
std::pair<double, double> distanceOf(const TPoint2& a, const TPoint2& b)
{
	const Eigen::Vector2d diff = a.p - b.p;
	const double n = diff.norm();
	const Eigen::Vector2d g = n > 0 ? Eigen::Vector2d(diff / n) : Eigen::Vector2d(1, 0);
	return {n, std::max(g.dot((a.C + b.C) * g), 1e-12)};
}
}  // namespace

TRigidTest rigidDistanceTest(const std::map<int, TPoint2>& a, const std::map<int, TPoint2>& b)
{
	std::vector<double> d, var;
	for (const auto& [step, pa] : a)
	{
		const auto it = b.find(step);
		if (it == b.end()) continue;
		const auto [n, v] = distanceOf(pa, it->second);
		d.push_back(n);
		var.push_back(v);
	}
	TRigidTest out;
	out.common = int(d.size());
	if (d.empty()) return out;
	double sw = 0, swd = 0;
	for (size_t i = 0; i < d.size(); ++i)
	{
		sw += 1 / var[i];
		swd += d[i] / var[i];
	}
	out.mean_dist = swd / sw;
	for (size_t i = 0; i < d.size(); ++i)
		out.chi2 += (d[i] - out.mean_dist) * (d[i] - out.mean_dist) / var[i];
	return out;
}

TRigidNow rigidNowTest(const std::map<int, TPoint2>& a, const TPoint2& za,
                       const std::map<int, TPoint2>& b, const TPoint2& zb)
{
	TRigidNow out;
	double sw = 0, swd = 0;
	for (const auto& [step, pa] : a)
	{
		const auto it = b.find(step);
		if (it == b.end()) continue;
		const auto [d, v] = distanceOf(pa, it->second);
		sw += 1 / v;
		swd += d / v;
		++out.past;
	}
	if (out.past == 0) return out;
	const auto [d, v] = distanceOf(za, zb);
	const double e = d - swd / sw;
	out.z2 = e * e / (v + 1 / sw);
	return out;
}
}  // namespace dynslam::estimator
