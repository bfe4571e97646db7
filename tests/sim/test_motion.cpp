/** Smooth profiles and trajectories of the simulator (pure math). */
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/motion.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynslam::sim;

namespace
{
double simpson(const CSmoothProfile& p, double t, int n = 40000)
{
	const double h = t / n;
	double s = p.value(0) + p.value(t);
	for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * p.value(i * h);
	return s * h / 3;
}
}  // namespace

TEST(SimMotion, ProfileValueRampsBetweenTargets)
{
	const CSmoothProfile p(10, {{5, 4, 14}, {20, 2, 8}});
	EXPECT_DOUBLE_EQ(p.value(0), 10);
	EXPECT_DOUBLE_EQ(p.value(5), 10);
	EXPECT_DOUBLE_EQ(p.value(7), 12);  // smoothstep(0.5) = 0.5
	EXPECT_DOUBLE_EQ(p.value(9), 14);
	EXPECT_DOUBLE_EQ(p.value(15), 14);
	EXPECT_DOUBLE_EQ(p.value(30), 8);
	const Eigen::Vector2d b = p.bounds(60);
	EXPECT_DOUBLE_EQ(b[0], 8);
	EXPECT_DOUBLE_EQ(b[1], 14);
}

TEST(SimMotion, IntegralAndDerivativeMatchNumerics)
{
	const CSmoothProfile p(3, {{1, 2.5, -1}, {6, 1, 4}}, 0.7, 0.9, 0.3);
	for (double t : {0.0, 0.5, 1.7, 3.4, 5.0, 6.3, 7.5, 12.0})
	{
		EXPECT_NEAR(p.integral(t), simpson(p, t), 1e-8 * std::max(1.0, std::abs(p.integral(t))))
		    << "t = " << t;
		const double h = 1e-6;
		EXPECT_NEAR(p.derivative(t), (p.value(t + h) - p.value(t - h)) / (2 * h), 1e-6)
		    << "t = " << t;
	}
}

TEST(SimMotion, RejectsOverlappingOrBadRamps)
{
	EXPECT_THROW(CSmoothProfile(0, {{5, 4, 1}, {8, 1, 2}}), std::invalid_argument);
	EXPECT_THROW(CSmoothProfile(0, {{5, 0, 1}}), std::invalid_argument);
	EXPECT_THROW(CSmoothProfile(0, {{-1, 2, 1}}), std::invalid_argument);
	EXPECT_THROW(CSmoothProfile(0, {{5, 1, 1}, {2, 1, 2}}), std::invalid_argument);
	EXPECT_NO_THROW(CSmoothProfile(0, {{5, 1, 1}, {6, 1, 2}}));
}

TEST(SimMotion, PoseHeadingFollowsVelocityOnBothTracks)
{
	for (double radius : {0.0, 150.0})
	{
		TTrack track;
		track.radius = radius;
		TBodyMotion m;
		m.s0 = 12;
		m.speed = CSmoothProfile(15, {{2, 3, 10}});
		m.lateral = CSmoothProfile(3.5, {{1, 4, 0}});
		for (double t : {0.0, 1.5, 2.9, 4.0, 7.0})
		{
			const double h = 1e-6;
			const Eigen::Vector3d a = m.pose(track, t - h), b = m.pose(track, t + h),
			                      x = m.pose(track, t);
			const Eigen::Vector2d v = (b.head<2>() - a.head<2>()) / (2 * h);
			EXPECT_NEAR(dynslam::models::wrapToPi(x[2] - std::atan2(v[1], v[0])), 0, 1e-7)
			    << "radius " << radius << " t " << t;
		}
	}
	// The track passes through the origin with heading 0.
	TTrack circle;
	circle.radius = 80;
	EXPECT_NEAR(circle.point(0, 0).norm(), 0, 1e-15);
	EXPECT_NEAR(circle.point(2 * M_PI * 80, 0).norm(), 0, 1e-12);
	EXPECT_NEAR((circle.point(80 * M_PI, 0) - Eigen::Vector2d(0, 160)).norm(), 0, 1e-12);
}

TEST(SimMotion, SpinningBodyAndFeatureLayouts)
{
	TBodyMotion m;
	m.spin = true;
	m.heading0 = 0.2;
	m.yaw_rate = -0.3;
	const TTrack track;
	EXPECT_NEAR(m.pose(track, 2)[2], 0.2 - 0.6, 1e-15);
	const Eigen::Matrix2Xd car = carCorners(4, 2);
	EXPECT_EQ(car.cols(), 4);
	EXPECT_NEAR(car.rowwise().mean().norm(), 0, 1e-15);
	for (int n : {1, 2, 3, 7})
	{
		const Eigen::Matrix2Xd e = ellipsePoints(n, 1.5, 0.5);
		EXPECT_EQ(e.cols(), n);
		EXPECT_NEAR(e.rowwise().mean().norm(), 0, 1e-15) << n;
	}
	const Eigen::Matrix2Xd w = bodyToWorld(Eigen::Vector3d(1, 2, M_PI / 2), car);
	EXPECT_NEAR(w(0, 0), 1 - 1, 1e-15);  // corner (2, 1) rotated by 90 deg -> (-1, 2)
	EXPECT_NEAR(w(1, 0), 2 + 2, 1e-15);
}
