/** Round trips and consistency of the core models: h(x, l(x, z)) = z, gamma(f0, g(xi, f0)) = xi
 * (all features and a subset seen, dtheta at the wrap), zero smoothing residual on
 * constant-velocity sequences across the wrap, wrapToPi, pose composition / difference. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/core/models/smoothing.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "core_test_utils.h"

using namespace dynslam::models;
using dynslam_test::uniform;
using Eigen::VectorXd;

namespace
{
/** Coordinates are up to ~100 m: double rounding in a few operations stays near 1e-13, so
 * 1e-9 m / 1e-9 rad are strict but safe bounds for an exact identity. */
constexpr double kTolPos = 1e-9;
constexpr double kTolAng = 1e-9;

std::vector<double> anglesWithWrap(int nRandom)
{
	std::vector<double> a;
	for (int i = 0; i < nRandom; ++i) a.push_back(uniform(-M_PI, M_PI));
	for (double th : core_test::wrapHeadings()) a.push_back(th);
	return a;
}
}  // namespace

TEST(AngleWrap, WrapToPi)
{
	EXPECT_EQ(wrapToPi(0.0), 0.0);
	EXPECT_EQ(wrapToPi(M_PI), M_PI);
	EXPECT_NEAR(wrapToPi(-M_PI), M_PI, 1e-15);
	EXPECT_NEAR(wrapToPi(3 * M_PI), M_PI, 1e-14);
	EXPECT_NEAR(wrapToPi(-3 * M_PI), M_PI, 1e-14);
	EXPECT_NEAR(wrapToPi(2 * M_PI + 0.1), 0.1, 1e-14);
	EXPECT_NEAR(wrapToPi(-2 * M_PI - 0.1), -0.1, 1e-14);
	dynslam_test::rng(201);
	for (int i = 0; i < 200; ++i)
	{
		const double a = uniform(-1e3, 1e3);
		const double w = wrapToPi(a);
		EXPECT_GT(w, -M_PI);
		EXPECT_LE(w, M_PI);
		const double turns = (a - w) / (2 * M_PI);
		EXPECT_NEAR(turns, std::round(turns), 1e-12) << "a = " << a;
	}
}

TEST(Se2RoundTrip, ComposeAndDifference)
{
	dynslam_test::rng(202);
	for (double th : anglesWithWrap(60))
	{
		const Eigen::Vector3d a(uniform(-50, 50), uniform(-50, 50), th);
		const Eigen::Vector3d b = core_test::randomPose();
		const Eigen::Vector3d u = poseDifference(b, a);
		const Eigen::Vector3d b2 = composePose(a, u);
		EXPECT_LT((b2.head<2>() - b.head<2>()).norm(), kTolPos);
		EXPECT_LT(std::abs(wrapToPi(b2[2] - b[2])), kTolAng);
		EXPECT_GT(u[2], -M_PI);
		EXPECT_LE(u[2], M_PI);
		// composePose matches the rigid-body formula out = p + R(theta) u_xy, theta + u_theta
		const Eigen::Vector2d p = a.head<2>() + rot2(a[2]) * u.head<2>();
		EXPECT_LT((p - b2.head<2>()).norm(), kTolPos);
	}
}

TEST(MeasurementRoundTrip, ObserveInverse)
{
	dynslam_test::rng(203);
	const auto angles = anglesWithWrap(60);
	for (MeasurementModel model : {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (size_t i = 0; i < angles.size(); ++i)
		{
			const Eigen::Vector3d x(uniform(-50, 50), uniform(-50, 50), angles[i]);
			const double b = angles[angles.size() - 1 - i];
			const double r = uniform(0.5, 60);
			const Eigen::Vector2d z = fromRangeBearing(model, r, b);
			// h(x, l(x, z)) = z
			const Eigen::Vector2d f = inverseObserve(model, x, z);
			const Eigen::Vector2d z2 = observe(model, x, f);
			const Eigen::Vector2d dz = innovation(model, z2, z);
			EXPECT_LT(std::abs(dz[0]), kTolPos) << toString(model);
			EXPECT_LT(std::abs(dz[1]), model == MeasurementModel::Cartesian ? kTolPos : kTolAng);
			// l(x, h(x, f)) = f
			const Eigen::Vector2d f2 = inverseObserve(model, x, observe(model, x, f));
			EXPECT_LT((f2 - f).norm(), kTolPos);
			// the stored reading describes the same point in both models
			const Eigen::Vector2d fc =
			    inverseObserve(MeasurementModel::Cartesian, x,
			                   fromRangeBearing(MeasurementModel::Cartesian, r, b));
			EXPECT_LT((fc - f).norm(), kTolPos);
			EXPECT_NEAR((f - x.head<2>()).norm(), r, kTolPos);
		}
}

TEST(MeasurementRoundTrip, ConversionsAndInnovation)
{
	dynslam_test::rng(204);
	for (double b : anglesWithWrap(60))
	{
		const Eigen::Vector2d rb(uniform(0.5, 60), b);
		const Eigen::Vector2d rb2 = cartesianToRangeBearing(rangeBearingToCartesian(rb));
		EXPECT_NEAR(rb2[0], rb[0], kTolPos);
		EXPECT_LT(std::abs(wrapToPi(rb2[1] - rb[1])), kTolAng);
		EXPECT_GT(rb2[1], -M_PI);
		EXPECT_LE(rb2[1], M_PI);
	}
	// the bearing innovation is wrapped for range-bearing, plain for Cartesian
	const Eigen::Vector2d z(5, M_PI - 0.01), zhat(5, -M_PI + 0.01);
	const Eigen::Vector2d nu = innovation(MeasurementModel::RangeBearing, z, zhat);
	EXPECT_NEAR(nu[0], 0, 1e-15);
	EXPECT_NEAR(nu[1], -0.02, 1e-12);
	EXPECT_NEAR(innovation(MeasurementModel::Cartesian, z, zhat)[1], 2 * M_PI - 0.02, 1e-12);
	// range-bearing observation bearing is wrapped into (-pi, pi]
	const Eigen::Vector3d x(0, 0, M_PI - 0.1);
	const Eigen::Vector2d zrb = rangeBearingObserve(x, Eigen::Vector2d(-1, -0.2));
	EXPECT_NEAR(zrb[1], wrapToPi(std::atan2(-0.2, -1) - x[2]), 1e-12);
	EXPECT_GT(zrb[1], -M_PI);
	EXPECT_LE(zrb[1], M_PI);
}

TEST(MeasurementModelNames, ParseAndPrint)
{
	EXPECT_EQ(measurementModelFromString("cartesian"), MeasurementModel::Cartesian);
	EXPECT_EQ(measurementModelFromString("Range_Bearing"), MeasurementModel::RangeBearing);
	EXPECT_EQ(measurementModelFromString(toString(MeasurementModel::RangeBearing)),
	          MeasurementModel::RangeBearing);
	EXPECT_EQ(measurementModelFromString(toString(MeasurementModel::Cartesian)),
	          MeasurementModel::Cartesian);
	EXPECT_THROW(measurementModelFromString("polar"), std::invalid_argument);
	EXPECT_THROW(measurementModelFromString(""), std::invalid_argument);
}

namespace
{
void expectPoseNear(const Eigen::Vector3d& got, const Eigen::Vector3d& want, const char* what)
{
	EXPECT_LT((got.head<2>() - want.head<2>()).norm(), kTolPos)
	    << what << ": got " << got.transpose() << " want " << want.transpose();
	EXPECT_LT(std::abs(wrapToPi(got[2] - want[2])), kTolAng)
	    << what << ": got " << got.transpose() << " want " << want.transpose();
}
}  // namespace

TEST(ObjectPoseRoundTrip, AllSeen)
{
	dynslam_test::rng(205);
	double worst = 0;
	for (int n = 2; n <= 8; ++n)
		for (double dth : anglesWithWrap(30))
		{
			const Eigen::Matrix2Xd f0 = core_test::randomObject(n);
			const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
			const Eigen::Vector3d xi2 = objectPoseInverse(f0, objectPoseMap(xi, f0));
			expectPoseNear(xi2, xi, "all seen");
			EXPECT_GT(xi2[2], -M_PI);
			EXPECT_LE(xi2[2], M_PI);
			worst = std::max(
			    {worst, (xi2.head<2>() - xi.head<2>()).norm(), std::abs(wrapToPi(xi2[2] - xi[2]))});
		}
	core_test::reportWorst("gamma(f0, g(xi, f0)) - xi, all seen", worst);
}

TEST(ObjectPoseRoundTrip, SubsetSeen)
{
	dynslam_test::rng(206);
	double worst = 0;
	for (int n = 3; n <= 8; ++n)
		for (double dth : anglesWithWrap(30))
		{
			const Eigen::Matrix2Xd f0 = core_test::randomObject(n);
			const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
			const Eigen::Matrix2Xd ftAll = objectPoseMap(xi, f0);
			std::vector<int> perm(size_t(n), 0);
			std::iota(perm.begin(), perm.end(), 0);
			std::shuffle(perm.begin(), perm.end(), dynslam_test::rng());
			const int m = 2 + int(dynslam_test::rng()() % unsigned(n - 2));
			const std::vector<int> seen(perm.begin(), perm.begin() + m);
			Eigen::Matrix2Xd ft(2, m);
			for (int i = 0; i < m; ++i) ft.col(i) = ftAll.col(seen[i]);
			const Eigen::Vector3d xi2 = objectPoseInverse(f0, ft, seen);
			expectPoseNear(xi2, xi, "subset seen");
			worst = std::max(
			    {worst, (xi2.head<2>() - xi.head<2>()).norm(), std::abs(wrapToPi(xi2[2] - xi[2]))});
			// the fitted pose predicts the unseen features too
			const Eigen::Matrix2Xd pred = objectPoseMap(xi2, f0);
			EXPECT_LT((pred - ftAll).cwiseAbs().maxCoeff(), kTolPos);
		}
	core_test::reportWorst("gamma(f0, g(xi, f0)[seen]) - xi", worst);
}

TEST(ObjectPoseRoundTrip, Collinear)
{
	dynslam_test::rng(207);
	for (int n = 2; n <= 6; ++n)
		for (double dth : anglesWithWrap(10))
		{
			// distinct features on one line (direction random)
			const Eigen::Vector2d base = core_test::randomVector(2, -30, 30);
			const double phi = uniform(-M_PI, M_PI);
			const Eigen::Vector2d dir(std::cos(phi), std::sin(phi));
			Eigen::Matrix2Xd f0(2, n);
			for (int k = 0; k < n; ++k) f0.col(k) = base + (1.0 + 1.5 * k + uniform(0, 1)) * dir;
			const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
			expectPoseNear(objectPoseInverse(f0, objectPoseMap(xi, f0)), xi, "collinear");
		}
}

TEST(ObjectPoseRoundTrip, TranslationOnly)
{
	dynslam_test::rng(208);
	for (int i = 0; i < 50; ++i)
	{
		const Eigen::Matrix2Xd f0 = core_test::randomObject(1);
		const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), uniform(-M_PI, M_PI));
		// a one-feature object rotates about itself: only the translation moves it
		const Eigen::Matrix2Xd ft = objectPoseMap(xi, f0);
		const Eigen::Vector2d t = objectTranslationInverse(f0.col(0), ft.col(0));
		EXPECT_LT((t - xi.head<2>()).norm(), kTolPos);
	}
}

TEST(SmoothingRoundTrip, ConstantVelocityIsZero)
{
	dynslam_test::rng(209);
	double worst = 0;
	for (double th0 : anglesWithWrap(50))
	{
		// constant velocity (dv, dw) with the heading crossing +-pi within the three steps
		const Eigen::Vector3d p0(uniform(-20, 20), uniform(-20, 20), th0);
		const Eigen::Vector3d v(uniform(-3, 3), uniform(-3, 3), uniform(-1.5, 1.5));
		std::vector<VectorXd> xi;
		for (int k = 0; k < 3; ++k)
		{
			Eigen::Vector3d p = p0 + k * v;
			p[2] = wrapToPi(p[2]);
			xi.emplace_back(p);
		}
		const VectorXd s = smoothingResidual(xi[0], xi[1], xi[2]);
		ASSERT_EQ(s.size(), 3);
		EXPECT_LT(s.cwiseAbs().maxCoeff(), 1e-12) << "theta0 = " << th0 << " s = " << s.transpose();
		worst = std::max(worst, s.cwiseAbs().maxCoeff());
		// 2-dof
		const VectorXd s2 = smoothingResidual(xi[0].head(2), xi[1].head(2), xi[2].head(2));
		ASSERT_EQ(s2.size(), 2);
		EXPECT_LT(s2.cwiseAbs().maxCoeff(), 1e-12);
		// an acceleration a gives s = a (heading component wrapped)
		const Eigen::Vector3d acc(uniform(-1, 1), uniform(-1, 1), uniform(-0.5, 0.5));
		Eigen::Vector3d c = xi[2] + acc;
		c[2] = wrapToPi(c[2]);
		const VectorXd sa = smoothingResidual(xi[0], xi[1], c);
		EXPECT_LT((sa - acc).cwiseAbs().maxCoeff(), 1e-12);
	}
	core_test::reportWorst("smoothing residual on constant velocity", worst);
}
