#pragma once
/** @file motion.h
 * Smooth, closed-form trajectories of the simulator (pure Eigen, no MRPT).
 *
 * Every moving body (the ego and each object) moves along a track (a straight line or a
 * circle through the origin, heading 0 at s = 0) with an along-track coordinate s(t) and a
 * lateral offset d(t) (positive to the left of the travel direction). Both come from
 * CSmoothProfile: a base value plus non-overlapping smoothstep ramps (S(u) = 3u^2 - 2u^3, so
 * velocity and acceleration are continuous) and an optional sine term. s(t) is the integral of
 * a speed profile; d(t) is a position profile. The heading is the direction of the velocity,
 * or, for spinning objects, a constant yaw rate. Everything is evaluated in O(#ramps) per
 * time, so generating N steps costs O(N). */
#include <Eigen/Core>
#include <limits>
#include <vector>

namespace dynslam::sim
{
/** One smooth change of a profile: from the previous value to `target` during
 * [t_start, t_start + duration]. */
struct TRamp
{
	double t_start = 0;
	double duration = 1;
	double target = 0;
};

/** v(t) = base + sum of smoothstep ramps + amp * sin(omega t + phase), t >= 0. */
class CSmoothProfile
{
public:
	CSmoothProfile() = default;
	/** Throws std::invalid_argument if ramps overlap, are unsorted, start before 0 or have
	 * non-positive duration (message says which ramp). */
	CSmoothProfile(double base, std::vector<TRamp> ramps, double sine_amp = 0,
	               double sine_omega = 0, double sine_phase = 0);

	double value(double t) const;
	double derivative(double t) const;
	/** Integral of value() from 0 to t. */
	double integral(double t) const;
	/** Smallest and largest value over [0, t_end] (ramps are monotone; sine adds +-amp). */
	Eigen::Vector2d bounds(double t_end) const;
	double base() const { return m_base; }
	const std::vector<TRamp>& ramps() const { return m_ramps; }

private:
	double m_base = 0;
	std::vector<TRamp> m_ramps;
	double m_amp = 0, m_omega = 0, m_phase = 0;
};

/** Track geometry: radius <= 0 means a straight line along +x. */
struct TTrack
{
	double radius = 0;
	/** World point at arc length s and lateral offset d (left of the travel direction). */
	Eigen::Vector2d point(double s, double d) const;
	/** Angle of the travel direction at s. */
	double tangentAngle(double s) const;
	/** Factor (1 - d / radius) that scales the along-track speed at offset d. */
	double speedScale(double d) const;
};

/** Motion of one rigid body. */
struct TBodyMotion
{
	double s0 = 0;           ///< along-track start
	CSmoothProfile speed;    ///< ds/dt [m/s]
	CSmoothProfile lateral;  ///< d(t) [m]
	bool spin = false;       ///< heading = heading0 + yaw_rate t instead of the velocity direction
	double heading0 = 0, yaw_rate = 0;
	/** The body rests from stop_time on: for t > stop_time the position is that at stop_time
	 * and the heading that at stop_heading_time (during the stopping ramp, where the speed is
	 * still positive: at rest atan2 of the velocity is undefined). +inf: never stops. */
	double stop_time = std::numeric_limits<double>::infinity();
	double stop_heading_time = std::numeric_limits<double>::infinity();

	/** World pose (x, y, theta) at time t on the given track. */
	Eigen::Vector3d pose(const TTrack& track, double t) const;
};

/** World positions (2 x n) of body-frame points `body` (2 x n) at pose x. */
Eigen::Matrix2Xd bodyToWorld(const Eigen::Vector3d& x, const Eigen::Matrix2Xd& body);

/** Body-frame feature layouts: a car's 4 corners; n points evenly on an ellipse with semi-axes
 * (a, b) (one point at the origin for n = 1; two points at (0, +-b) for n = 2). */
Eigen::Matrix2Xd carCorners(double length, double width);
Eigen::Matrix2Xd ellipsePoints(int n, double a, double b);
}  // namespace dynslam::sim
