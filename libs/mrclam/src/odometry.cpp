#include <dynslam/mrclam/odometry.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::mrclam
{
double wrapAngle(double a)
{
	a = std::fmod(a + M_PI, 2 * M_PI);
	if (a <= 0) a += 2 * M_PI;
	return a - M_PI;
}

Eigen::Vector3d unicycleArc(double v, double w, double dt)
{
	const double th = w * dt;
	if (std::abs(th) < 1e-9)
	{
		// second-order expansion: exact to ~1e-27 for such small angles
		return {v * dt * (1 - th * th / 6), v * dt * th / 2, th};
	}
	return {v / w * std::sin(th), v / w * (1 - std::cos(th)), th};
}

Eigen::Vector3d composeSE2(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
	const double c = std::cos(a.z()), s = std::sin(a.z());
	return {a.x() + c * b.x() - s * b.y(), a.y() + s * b.x() + c * b.y(), wrapAngle(a.z() + b.z())};
}

Eigen::Vector3d relativeSE2(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
	const double c = std::cos(a.z()), s = std::sin(a.z());
	const double dx = b.x() - a.x(), dy = b.y() - a.y();
	return {c * dx + s * dy, -s * dx + c * dy, wrapAngle(b.z() - a.z())};
}

COdometryIntegrator::COdometryIntegrator(std::vector<TOdometryRow> rows, double delay,
                                         double scaleV, double scaleW)
    : m_rows(std::move(rows))
{
	if (!std::isfinite(delay) || !std::isfinite(scaleV) || !std::isfinite(scaleW))
		throw std::invalid_argument("COdometryIntegrator: delay or gains not finite");
	for (auto& r : m_rows)
	{
		r.t += delay;
		r.v *= scaleV;
		r.w *= scaleW;
	}
	for (size_t i = 1; i < m_rows.size(); i++)
		if (m_rows[i].t < m_rows[i - 1].t)
			throw std::invalid_argument("COdometryIntegrator: rows not sorted by time");
}

TOdometryIncrement COdometryIntegrator::integrate(double ta, double tb) const
{
	if (!(tb >= ta))
		throw std::invalid_argument("COdometryIntegrator::integrate: tb < ta (" +
		                            std::to_string(tb) + " < " + std::to_string(ta) + ")");
	TOdometryIncrement inc;
	if (m_rows.empty() || tb == ta) return inc;
	// first row whose time is > ta; the command active at ta is the one before it
	auto it = std::upper_bound(m_rows.begin(), m_rows.end(), ta,
	                           [](double t, const TOdometryRow& r) { return t < r.t; });
	double t = ta;
	if (it == m_rows.begin())
	{
		t = std::min(tb, it->t);  // standing still before the first row
		++it;
	}
	while (t < tb)
	{
		const auto& cmd = *(it - 1);
		const double tEndPiece = (it == m_rows.end()) ? tb : std::min(tb, it->t);
		const double dt = tEndPiece - t;
		if (dt > 0)
		{
			inc.delta = composeSE2(inc.delta, unicycleArc(cmd.v, cmd.w, dt));
			inc.distance += std::abs(cmd.v) * dt;
			inc.angle += std::abs(cmd.w) * dt;
		}
		t = tEndPiece;
		if (it != m_rows.end()) ++it;
	}
	return inc;
}

Eigen::Matrix3d TOdometryNoiseModel::covariance(const TOdometryIncrement& inc) const
{
	const double vxy =
	    std_xy_min * std_xy_min + var_xy_per_m * inc.distance + var_xy_per_rad * inc.angle;
	const double vphi =
	    std_phi_min * std_phi_min + var_phi_per_m * inc.distance + var_phi_per_rad * inc.angle;
	const bool infl = model == Model::inflated;
	const double kxy = infl ? tau_xy : 1.0, kphi = infl ? tau_phi : 1.0;
	return Eigen::Vector3d(kxy * vxy, kxy * vxy, kphi * vphi).asDiagonal();
}

CTrajectoryInterpolator::CTrajectoryInterpolator(std::vector<TPoseRow> rows)
    : m_rows(std::move(rows))
{
	if (m_rows.size() < 2)
		throw std::invalid_argument("CTrajectoryInterpolator: fewer than 2 poses");
	for (size_t i = 1; i < m_rows.size(); i++)
		if (m_rows[i].t < m_rows[i - 1].t)
			throw std::invalid_argument("CTrajectoryInterpolator: rows not sorted by time");
}

Eigen::Vector3d CTrajectoryInterpolator::at(double t) const
{
	if (!covers(t))
		throw std::out_of_range("ground truth does not cover t = " + std::to_string(t) +
		                        " (covers [" + std::to_string(tBegin()) + ", " +
		                        std::to_string(tEnd()) + "])");
	auto it = std::lower_bound(m_rows.begin(), m_rows.end(), t,
	                           [](const TPoseRow& r, double tt) { return r.t < tt; });
	if (it == m_rows.begin()) return {it->x, it->y, wrapAngle(it->theta)};
	const auto& b = *it;
	const auto& a = *(it - 1);
	const double dt = b.t - a.t;
	const double s = dt > 0 ? (t - a.t) / dt : 1.0;
	const double dth = wrapAngle(b.theta - a.theta);
	return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), wrapAngle(a.theta + s * dth)};
}

double CTrajectoryInterpolator::maxGap(double ta, double tb) const
{
	double g = 0;
	for (size_t i = 1; i < m_rows.size(); i++)
		if (m_rows[i].t >= ta && m_rows[i - 1].t <= tb)
			g = std::max(g, m_rows[i].t - m_rows[i - 1].t);
	return g;
}
}  // namespace dynslam::mrclam
