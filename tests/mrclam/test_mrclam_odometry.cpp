/** Exact odometry integration, the noise model and ground-truth interpolation. */
#include <dynslam/mrclam/odometry.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynslam::mrclam;

namespace
{
/** Fine Euler integration of the unicycle (reference for the closed form). */
Eigen::Vector3d euler(double v, double w, double dt, int n = 200000)
{
	Eigen::Vector3d p = Eigen::Vector3d::Zero();
	const double h = dt / n;
	for (int i = 0; i < n; i++)
	{
		const double th = p.z() + 0.5 * w * h;  // midpoint heading
		p.x() += v * h * std::cos(th);
		p.y() += v * h * std::sin(th);
		p.z() += w * h;
	}
	return p;
}
}  // namespace

TEST(MrclamOdometry, UnicycleArcMatchesFineIntegration)
{
	for (const auto& [v, w, dt] : std::vector<std::array<double, 3>>{{0.1, 0.4, 1.3},
	                                                                 {0.2, -1.5, 2.0},
	                                                                 {-0.1, 0.3, 0.7},
	                                                                 {0.15, 0.0, 1.0},
	                                                                 {0.0, 0.5, 1.0},
	                                                                 {0.1, 1e-12, 3.0}})
	{
		const Eigen::Vector3d a = unicycleArc(v, w, dt);
		const Eigen::Vector3d e = euler(v, w, dt);
		EXPECT_NEAR(a.x(), e.x(), 1e-9) << v << " " << w;
		EXPECT_NEAR(a.y(), e.y(), 1e-9) << v << " " << w;
		EXPECT_NEAR(a.z(), e.z(), 1e-9);  // round-off of the 2e5-step sum
	}
	// a full circle returns to the start
	const Eigen::Vector3d c = unicycleArc(0.2, 0.5, 2 * M_PI / 0.5);
	EXPECT_NEAR(c.x(), 0, 1e-12);
	EXPECT_NEAR(c.y(), 0, 1e-12);
}

TEST(MrclamOdometry, ComposeAndRelativeAreInverse)
{
	const Eigen::Vector3d a(1.0, -2.0, 3.0), b(0.3, 0.4, 0.5);
	const Eigen::Vector3d c = composeSE2(a, b);
	const Eigen::Vector3d r = relativeSE2(a, c);
	EXPECT_NEAR((r - b).norm(), 0, 1e-12);
	EXPECT_NEAR(wrapAngle(3 * M_PI), M_PI, 1e-12);
	EXPECT_NEAR(wrapAngle(-M_PI), M_PI, 1e-12);
	EXPECT_NEAR(wrapAngle(0.5 - 4 * M_PI), 0.5, 1e-12);
}

TEST(MrclamOdometry, ZeroOrderHoldPiecesAndStandstill)
{
	// commands: t=1: (0.1, 0), t=2: (0.1, 0.5), t=3: (0, 0)
	const COdometryIntegrator odo({{1.0, 0.1, 0.0}, {2.0, 0.1, 0.5}, {3.0, 0.0, 0.0}});
	// before the first command: standing still
	EXPECT_NEAR(odo.integrate(0.0, 1.0).delta.norm(), 0, 1e-15);
	// one piece
	const auto a = odo.integrate(1.2, 1.7);
	EXPECT_NEAR(a.delta.x(), 0.05, 1e-12);
	EXPECT_NEAR(a.distance, 0.05, 1e-12);
	// across pieces = composition of the pieces
	const auto ab = odo.integrate(0.5, 2.6);
	const Eigen::Vector3d ref = composeSE2(unicycleArc(0.1, 0, 1.0), unicycleArc(0.1, 0.5, 0.6));
	EXPECT_NEAR((ab.delta - ref).norm(), 0, 1e-12);
	EXPECT_NEAR(ab.distance, 0.16, 1e-12);
	EXPECT_NEAR(ab.angle, 0.3, 1e-12);
	// additivity: [t0,t1] (+) [t1,t2] == [t0,t2]
	const auto p1 = odo.integrate(1.5, 2.25), p2 = odo.integrate(2.25, 5.0);
	const auto all = odo.integrate(1.5, 5.0);
	EXPECT_NEAR((composeSE2(p1.delta, p2.delta) - all.delta).norm(), 0, 1e-12);
	// the last command (0, 0) holds until the end
	EXPECT_NEAR(odo.integrate(3.0, 100.0).delta.norm(), 0, 1e-15);
	EXPECT_THROW(odo.integrate(2.0, 1.0), std::invalid_argument);
}

TEST(MrclamOdometry, DelayShiftsTheCommandsAndGainsScaleThem)
{
	const std::vector<TOdometryRow> rows = {{1.0, 0.1, 0.2}, {2.0, 0.0, 0.0}};
	const COdometryIntegrator plain(rows), delayed(rows, 0.25), scaled(rows, 0.0, 0.5, 2.0);
	const auto a = plain.integrate(1.0, 2.0);
	const auto b = delayed.integrate(1.25, 2.25);
	EXPECT_NEAR((a.delta - b.delta).norm(), 0, 1e-15);
	// with the delay, [1, 1.25) is still before the first command
	EXPECT_NEAR(delayed.integrate(1.0, 1.25).delta.norm(), 0, 1e-15);
	const auto s = scaled.integrate(1.0, 2.0);
	EXPECT_NEAR((s.delta - unicycleArc(0.05, 0.4, 1.0)).norm(), 0, 1e-15);
}

TEST(MrclamOdometry, NoiseModelGrowsWithDistanceAndAngle)
{
	TOdometryNoiseModel m;
	m.std_xy_min = 0.01;
	m.var_xy_per_m = 2e-4;
	m.var_xy_per_rad = 1e-4;
	m.std_phi_min = 0.02;
	m.var_phi_per_m = 3e-3;
	m.var_phi_per_rad = 7e-3;
	TOdometryIncrement inc;
	inc.distance = 2.0;
	inc.angle = 0.5;
	const Eigen::Matrix3d C = m.covariance(inc);
	EXPECT_NEAR(C(0, 0), 1e-4 + 4e-4 + 0.5e-4, 1e-15);
	EXPECT_NEAR(C(1, 1), C(0, 0), 1e-18);
	EXPECT_NEAR(C(2, 2), 4e-4 + 6e-3 + 3.5e-3, 1e-15);
	EXPECT_EQ(C(0, 1), 0.0);
	EXPECT_EQ(C(0, 2), 0.0);
	// additivity of a random walk: two halves give the variance of the whole minus one floor
	TOdometryIncrement half = inc;
	half.distance = 1.0;
	half.angle = 0.25;
	const Eigen::Matrix3d Ch = m.covariance(half);
	EXPECT_NEAR(2 * Ch(0, 0) - m.std_xy_min * m.std_xy_min, C(0, 0), 1e-15);
	// the taus only act with the inflated model: var_xy * tau_xy, var_phi * tau_phi
	m.tau_xy = 15;
	m.tau_phi = 3;
	EXPECT_EQ(m.covariance(inc), C);
	m.model = TOdometryNoiseModel::Model::inflated;
	const Eigen::Matrix3d Ci = m.covariance(inc);
	EXPECT_NEAR(Ci(0, 0), 15 * C(0, 0), 1e-15);
	EXPECT_NEAR(Ci(1, 1), 15 * C(1, 1), 1e-15);
	EXPECT_NEAR(Ci(2, 2), 3 * C(2, 2), 1e-15);
	EXPECT_EQ(Ci(0, 1), 0.0);
}

TEST(MrclamOdometry, InterpolationWrapsTheAngle)
{
	const CTrajectoryInterpolator tr(
	    {{0.0, 0.0, 0.0, 3.0}, {1.0, 1.0, 2.0, -3.0}, {2.0, 1.0, 2.0, -3.0}});
	const Eigen::Vector3d p = tr.at(0.5);
	EXPECT_NEAR(p.x(), 0.5, 1e-12);
	EXPECT_NEAR(p.y(), 1.0, 1e-12);
	// from 3.0 to -3.0 the short way goes through pi: the midpoint is pi (or -pi)
	EXPECT_NEAR(std::abs(p.z()), M_PI, 1e-12);
	EXPECT_NEAR(tr.at(0.25).z(), 3.0 + 0.25 * (2 * M_PI - 6.0), 1e-12);
	EXPECT_NEAR((tr.at(1.0) - Eigen::Vector3d(1, 2, -3)).norm(), 0, 1e-12);
	EXPECT_THROW(tr.at(-0.1), std::out_of_range);
	EXPECT_THROW(tr.at(2.1), std::out_of_range);
	EXPECT_DOUBLE_EQ(tr.maxGap(0.0, 2.0), 1.0);
}
