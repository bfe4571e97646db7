#include <dynslam/core/models/se2.h>
#include <dynslam/sim/motion.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::sim
{
namespace
{
double smoothstep(double u)
{
	if (u <= 0) return 0;
	if (u >= 1) return 1;
	return u * u * (3 - 2 * u);
}
double smoothstepDerivative(double u) { return (u <= 0 || u >= 1) ? 0 : 6 * u * (1 - u); }
/** Integral of smoothstep from 0 to u. */
double smoothstepIntegral(double u)
{
	if (u <= 0) return 0;
	if (u >= 1) return u - 0.5;
	return u * u * u - 0.5 * u * u * u * u;
}
}  // namespace

CSmoothProfile::CSmoothProfile(double base, std::vector<TRamp> ramps, double sine_amp,
                               double sine_omega, double sine_phase)
    : m_base(base),
      m_ramps(std::move(ramps)),
      m_amp(sine_amp),
      m_omega(sine_omega),
      m_phase(sine_phase)
{
	double prevEnd = 0;
	for (size_t i = 0; i < m_ramps.size(); ++i)
	{
		const TRamp& r = m_ramps[i];
		const std::string which =
		    "ramp " + std::to_string(i + 1) + " (t_start " + std::to_string(r.t_start) + ")";
		if (!std::isfinite(r.t_start) || !std::isfinite(r.duration) || !std::isfinite(r.target))
			throw std::invalid_argument(which + ": not finite");
		if (!(r.duration > 0)) throw std::invalid_argument(which + ": duration must be > 0");
		if (r.t_start < prevEnd)
			throw std::invalid_argument(
			    which +
			    (i == 0 ? ": starts before t = 0" : ": overlaps the previous ramp or is unsorted"));
		prevEnd = r.t_start + r.duration;
	}
	if (!std::isfinite(base) || !std::isfinite(sine_amp) || !std::isfinite(sine_omega) ||
	    !std::isfinite(sine_phase))
		throw std::invalid_argument("profile: base or sine parameters not finite");
}

double CSmoothProfile::value(double t) const
{
	double v = m_base, prev = m_base;
	for (const TRamp& r : m_ramps)
	{
		v += (r.target - prev) * smoothstep((t - r.t_start) / r.duration);
		prev = r.target;
	}
	if (m_amp != 0) v += m_amp * std::sin(m_omega * t + m_phase);
	return v;
}

double CSmoothProfile::derivative(double t) const
{
	double d = 0, prev = m_base;
	for (const TRamp& r : m_ramps)
	{
		d += (r.target - prev) * smoothstepDerivative((t - r.t_start) / r.duration) / r.duration;
		prev = r.target;
	}
	if (m_amp != 0) d += m_amp * m_omega * std::cos(m_omega * t + m_phase);
	return d;
}

double CSmoothProfile::integral(double t) const
{
	double I = m_base * t, prev = m_base;
	for (const TRamp& r : m_ramps)
	{
		I += (r.target - prev) * r.duration * smoothstepIntegral((t - r.t_start) / r.duration);
		prev = r.target;
	}
	if (m_amp != 0)
	{
		if (m_omega != 0)
			I += m_amp / m_omega * (std::cos(m_phase) - std::cos(m_omega * t + m_phase));
		else
			I += m_amp * std::sin(m_phase) * t;
	}
	return I;
}

Eigen::Vector2d CSmoothProfile::bounds(double t_end) const
{
	// Without the sine the profile is monotone between ramp ends: check base, ramp ends, t_end.
	const CSmoothProfile plain(m_base, m_ramps);
	double lo = m_base, hi = m_base;
	auto take = [&](double t)
	{
		const double v = plain.value(std::min(t, t_end));
		lo = std::min(lo, v);
		hi = std::max(hi, v);
	};
	for (const TRamp& r : m_ramps) take(r.t_start + r.duration);
	take(t_end);
	return {lo - std::abs(m_amp), hi + std::abs(m_amp)};
}

Eigen::Vector2d TTrack::point(double s, double d) const
{
	if (radius <= 0) return {s, d};
	const double phi = s / radius;
	return {(radius - d) * std::sin(phi), radius - (radius - d) * std::cos(phi)};
}

double TTrack::tangentAngle(double s) const { return radius <= 0 ? 0.0 : s / radius; }

double TTrack::speedScale(double d) const { return radius <= 0 ? 1.0 : 1.0 - d / radius; }

Eigen::Vector3d TBodyMotion::pose(const TTrack& track, double t) const
{
	if (t > stop_time)
	{
		const Eigen::Vector3d rest = pose(track, stop_time);
		return {rest[0], rest[1], pose(track, stop_heading_time)[2]};
	}
	const double s = s0 + speed.integral(t), d = lateral.value(t);
	const Eigen::Vector2d p = track.point(s, d);
	double th;
	if (spin)
		th = heading0 + yaw_rate * t;
	else
		th = track.tangentAngle(s) +
		     std::atan2(lateral.derivative(t), speed.value(t) * track.speedScale(d));
	return {p[0], p[1], models::wrapToPi(th)};
}

Eigen::Matrix2Xd bodyToWorld(const Eigen::Vector3d& x, const Eigen::Matrix2Xd& body)
{
	return (models::rot2(x[2]) * body).colwise() + x.head<2>();
}

Eigen::Matrix2Xd carCorners(double length, double width)
{
	Eigen::Matrix2Xd b(2, 4);
	const double a = length / 2, c = width / 2;
	b << a, a, -a, -a, c, -c, -c, c;
	return b;
}

Eigen::Matrix2Xd ellipsePoints(int n, double a, double b)
{
	if (n < 1) throw std::invalid_argument("ellipsePoints: need at least one feature");
	Eigen::Matrix2Xd p(2, n);
	if (n == 1)
	{
		p.setZero();
		return p;
	}
	if (n == 2)
	{
		p << 0, 0, b, -b;
		return p;
	}
	for (int j = 0; j < n; ++j)
	{
		const double ang = 2 * M_PI * (j + 0.5) / n;
		p.col(j) << a * std::cos(ang), b * std::sin(ang);
	}
	return p;
}
}  // namespace dynslam::sim
