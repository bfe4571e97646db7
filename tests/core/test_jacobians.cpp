/** Every analytic Jacobian of dynslam::core's models vs central differences (relative error
 * <= 1e-6) at >= 50 seeded random states each, plus states at the +-pi wrap. Angle outputs
 * are unwrapped relative to the nominal value before differencing. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/core/models/smoothing.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "core_test_utils.h"

using namespace dynslam::models;
using core_test::checkJacobian;
using core_test::VecFn;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
constexpr int kRandomStates = 60;

/** Random poses followed by poses whose heading sits at the wrap. */
std::vector<Eigen::Vector3d> testPoses()
{
	std::vector<Eigen::Vector3d> poses;
	for (int i = 0; i < kRandomStates; ++i) poses.push_back(core_test::randomPose());
	for (double th : core_test::wrapHeadings())
		poses.emplace_back(uniform(-50, 50), uniform(-50, 50), th);
	return poses;
}

/** Random angles in (-pi, pi] followed by the wrap angles. */
std::vector<double> testAngles()
{
	std::vector<double> a;
	for (int i = 0; i < kRandomStates; ++i) a.push_back(uniform(-M_PI, M_PI));
	for (double th : core_test::wrapHeadings()) a.push_back(th);
	return a;
}

/** A point at distance r in [1, 40] and bearing b (relative to the heading) from pose x. */
Eigen::Vector2d pointAt(const Eigen::Vector3d& x, double b)
{
	const double r = uniform(1, 40);
	return x.head<2>() + r * Eigen::Vector2d(std::cos(x[2] + b), std::sin(x[2] + b));
}
}  // namespace

TEST(Se2Jacobians, ComposePose)
{
	dynslam_test::rng(101);
	double worst = 0;
	const auto poses = testPoses();
	const auto angles = testAngles();
	for (size_t i = 0; i < poses.size(); ++i)
	{
		const Eigen::Vector3d x = poses[i];
		// increments: random, and (for the wrap states) small turns that cross +-pi
		Eigen::Vector3d u(uniform(-5, 5), uniform(-5, 5), angles[i]);
		if (i >= size_t(kRandomStates)) u[2] = (i % 2 ? 1 : -1) * 1e-9 * double(i % 3);
		Eigen::Matrix3d J_out_x, J_out_u;
		composePose(x, u, &J_out_x, &J_out_u);
		const VecFn fx = [&](const VectorXd& v) { return VectorXd(composePose(v, u)); };
		const VecFn fu = [&](const VectorXd& v) { return VectorXd(composePose(x, v)); };
		EXPECT_TRUE(checkJacobian(J_out_x, fx, x, {2}, worst)) << "J_out_x, u = " << u.transpose();
		EXPECT_TRUE(checkJacobian(J_out_u, fu, u, {2}, worst)) << "J_out_u, x = " << x.transpose();
	}
	core_test::reportWorst("composePose", worst);
}

TEST(MeasurementJacobians, Cartesian)
{
	dynslam_test::rng(102);
	double worst = 0;
	const auto angles = testAngles();
	int k = 0;
	for (const Eigen::Vector3d& x : testPoses())
	{
		for (double b : {angles[size_t(k++) % angles.size()], M_PI - 1e-9, M_PI})
		{
			const Eigen::Vector2d f = pointAt(x, b);
			Matrix23d J_z_x;
			Eigen::Matrix2d J_z_f;
			const Eigen::Vector2d z = cartesianObserve(x, f, &J_z_x, &J_z_f);
			EXPECT_TRUE(checkJacobian(
			    J_z_x, [&](const VectorXd& v) { return VectorXd(cartesianObserve(v, f)); }, x, {},
			    worst));
			EXPECT_TRUE(checkJacobian(
			    J_z_f, [&](const VectorXd& v) { return VectorXd(cartesianObserve(x, v)); }, f, {},
			    worst));

			Matrix23d J_f_x;
			Eigen::Matrix2d J_f_z;
			cartesianInverse(x, z, &J_f_x, &J_f_z);
			EXPECT_TRUE(checkJacobian(
			    J_f_x, [&](const VectorXd& v) { return VectorXd(cartesianInverse(v, z)); }, x, {},
			    worst));
			EXPECT_TRUE(checkJacobian(
			    J_f_z, [&](const VectorXd& v) { return VectorXd(cartesianInverse(x, v)); }, z, {},
			    worst));
		}
	}
	core_test::reportWorst("cartesian observe/inverse", worst);
}

TEST(MeasurementJacobians, RangeBearing)
{
	dynslam_test::rng(103);
	double worst = 0;
	const auto angles = testAngles();
	int k = 0;
	for (const Eigen::Vector3d& x : testPoses())
	{
		// bearings: random, and at the +-pi wrap of the bearing itself
		for (double b : {angles[size_t(k++) % angles.size()], M_PI - 1e-9, -M_PI + 1e-9, M_PI})
		{
			const Eigen::Vector2d f = pointAt(x, b);
			Matrix23d J_z_x;
			Eigen::Matrix2d J_z_f;
			const Eigen::Vector2d z = rangeBearingObserve(x, f, &J_z_x, &J_z_f);
			EXPECT_TRUE(checkJacobian(
			    J_z_x, [&](const VectorXd& v) { return VectorXd(rangeBearingObserve(v, f)); }, x,
			    {1}, worst));
			EXPECT_TRUE(checkJacobian(
			    J_z_f, [&](const VectorXd& v) { return VectorXd(rangeBearingObserve(x, v)); }, f,
			    {1}, worst));

			Matrix23d J_f_x;
			Eigen::Matrix2d J_f_z;
			rangeBearingInverse(x, z, &J_f_x, &J_f_z);
			EXPECT_TRUE(checkJacobian(
			    J_f_x, [&](const VectorXd& v) { return VectorXd(rangeBearingInverse(v, z)); }, x,
			    {}, worst));
			EXPECT_TRUE(checkJacobian(
			    J_f_z, [&](const VectorXd& v) { return VectorXd(rangeBearingInverse(x, v)); }, z,
			    {}, worst));
		}
	}
	core_test::reportWorst("range-bearing observe/inverse", worst);
}

TEST(MeasurementJacobians, Conversions)
{
	dynslam_test::rng(104);
	double worst = 0;
	for (double b : testAngles())
	{
		const Eigen::Vector2d rb(uniform(0.5, 60), b);
		Eigen::Matrix2d J_c_rb, J_rb_c;
		const Eigen::Vector2d c = rangeBearingToCartesian(rb, &J_c_rb);
		EXPECT_TRUE(checkJacobian(
		    J_c_rb, [](const VectorXd& v) { return VectorXd(rangeBearingToCartesian(v)); }, rb, {},
		    worst));
		cartesianToRangeBearing(c, &J_rb_c);
		EXPECT_TRUE(checkJacobian(
		    J_rb_c, [](const VectorXd& v) { return VectorXd(cartesianToRangeBearing(v)); }, c, {1},
		    worst));
	}
	// on the negative x axis (bearing exactly pi) and just either side of it
	for (double y : {0.0, 1e-9, -1e-9})
	{
		const Eigen::Vector2d c(-uniform(0.5, 60), y);
		Eigen::Matrix2d J_rb_c;
		cartesianToRangeBearing(c, &J_rb_c);
		EXPECT_TRUE(checkJacobian(
		    J_rb_c, [](const VectorXd& v) { return VectorXd(cartesianToRangeBearing(v)); }, c, {1},
		    worst));
	}
	core_test::reportWorst("rb <-> cartesian conversions", worst);
}

TEST(ObjectPoseJacobians, PoseMap)
{
	dynslam_test::rng(105);
	double worst = 0;
	const auto angles = testAngles();
	for (int n = 1; n <= 6; ++n)
	{
		for (double dth : angles)
		{
			const Eigen::Matrix2Xd f0 = core_test::randomObject(n);
			const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
			MatrixXd J_ft_xi, J_ft_f0;
			objectPoseMap(xi, f0, &J_ft_xi, &J_ft_f0);
			EXPECT_TRUE(checkJacobian(
			    J_ft_xi, [&](const VectorXd& v) { return core_test::vec(objectPoseMap(v, f0)); },
			    xi, {}, worst))
			    << "n = " << n;
			EXPECT_TRUE(checkJacobian(
			    J_ft_f0,
			    [&](const VectorXd& v)
			    { return core_test::vec(objectPoseMap(xi, core_test::unvec(v))); },
			    core_test::vec(f0), {}, worst))
			    << "n = " << n;
		}
	}
	core_test::reportWorst("objectPoseMap", worst);
}

namespace
{
/** Gamma1 / Gamma2 of objectPoseInverse vs numeric, for f0 (2 x n) and ft = g(xi, f0[seen])
 * perturbed by noise (so the fit is not exact and the check covers non-rigid inputs too). */
void checkGammas(const Eigen::Matrix2Xd& f0, const Eigen::Vector3d& xi,
                 const std::vector<int>& seen, double noise, double& worst)
{
	const Eigen::Matrix2Xd ftAll = objectPoseMap(xi, f0);
	const int m = seen.empty() ? int(f0.cols()) : int(seen.size());
	Eigen::Matrix2Xd ft(2, m);
	for (int i = 0; i < m; ++i)
		ft.col(i) = ftAll.col(seen.empty() ? i : seen[i]) +
		            Eigen::Vector2d(uniform(-noise, noise), uniform(-noise, noise));
	MatrixXd G1, G2;
	objectPoseInverse(f0, ft, seen, &G1, &G2);
	ASSERT_EQ(G1.rows(), 3);
	ASSERT_EQ(G1.cols(), 2 * f0.cols());
	ASSERT_EQ(G2.cols(), 2 * m);
	EXPECT_TRUE(checkJacobian(
	    G1,
	    [&](const VectorXd& v)
	    { return VectorXd(objectPoseInverse(core_test::unvec(v), ft, seen)); },
	    core_test::vec(f0), {2}, worst))
	    << "Gamma1, n = " << f0.cols() << ", m = " << m << ", dtheta = " << xi[2];
	EXPECT_TRUE(checkJacobian(
	    G2,
	    [&](const VectorXd& v)
	    { return VectorXd(objectPoseInverse(f0, core_test::unvec(v), seen)); },
	    core_test::vec(ft), {2}, worst))
	    << "Gamma2, n = " << f0.cols() << ", m = " << m << ", dtheta = " << xi[2];
}
}  // namespace

TEST(ObjectPoseJacobians, InverseAllSeen)
{
	dynslam_test::rng(106);
	double worst = 0;
	const auto angles = testAngles();
	for (int n = 2; n <= 8; ++n)
		for (double dth : angles)
		{
			const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
			checkGammas(core_test::randomObject(n), xi, {}, 0.05, worst);
		}
	core_test::reportWorst("objectPoseInverse all seen", worst);
}

TEST(ObjectPoseJacobians, InverseSubsetSeen)
{
	dynslam_test::rng(107);
	double worst = 0;
	const auto angles = testAngles();
	for (int n = 3; n <= 8; ++n)
		for (double dth : angles)
		{
			// a random strict subset of >= 2 features, in random order
			std::vector<int> perm(size_t(n), 0);
			std::iota(perm.begin(), perm.end(), 0);
			std::shuffle(perm.begin(), perm.end(), dynslam_test::rng());
			const int m = 2 + int(dynslam_test::rng()() % unsigned(n - 2));
			const std::vector<int> seen(perm.begin(), perm.begin() + m);
			const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
			checkGammas(core_test::randomObject(n), xi, seen, 0.05, worst);
		}
	core_test::reportWorst("objectPoseInverse subset seen", worst);
}

TEST(ObjectPoseJacobians, TranslationInverse)
{
	dynslam_test::rng(108);
	double worst = 0;
	for (int i = 0; i < kRandomStates; ++i)
	{
		const Eigen::Vector2d f0 = core_test::randomVector(2, -50, 50);
		const Eigen::Vector2d ft = core_test::randomVector(2, -50, 50);
		Eigen::Matrix2d G1, G2;
		objectTranslationInverse(f0, ft, &G1, &G2);
		EXPECT_TRUE(checkJacobian(
		    G1, [&](const VectorXd& v) { return VectorXd(objectTranslationInverse(v, ft)); }, f0,
		    {}, worst));
		EXPECT_TRUE(checkJacobian(
		    G2, [&](const VectorXd& v) { return VectorXd(objectTranslationInverse(f0, v)); }, ft,
		    {}, worst));
	}
	core_test::reportWorst("objectTranslationInverse", worst);
}

namespace
{
void checkSmoothingJacobians(int d, double& worst)
{
	const auto angles = testAngles();
	for (size_t i = 0; i < angles.size(); ++i)
	{
		VectorXd abc = core_test::randomVector(3 * d, -10, 10);
		if (d == 3)
		{
			// headings: random, or all three at the wrap on alternating sides
			const double th = angles[i];
			abc[2] = th;
			abc[5] = wrapToPi(th + (i % 2 ? 1e-9 : uniform(-1, 1)));
			abc[8] = wrapToPi(th - (i % 2 ? 1e-9 : uniform(-1, 1)));
		}
		MatrixXd Ja, Jb, Jc;
		smoothingResidual(abc.segment(0, d), abc.segment(d, d), abc.segment(2 * d, d), &Ja, &Jb,
		                  &Jc);
		MatrixXd J(d, 3 * d);
		J << Ja, Jb, Jc;
		const VecFn f = [d](const VectorXd& v)
		{ return smoothingResidual(v.segment(0, d), v.segment(d, d), v.segment(2 * d, d)); };
		std::vector<int> angleOut;
		if (d == 3) angleOut.push_back(2);
		EXPECT_TRUE(checkJacobian(J, f, abc, angleOut, worst)) << "d = " << d;
	}
}
}  // namespace

TEST(SmoothingJacobians, ThreeDof)
{
	dynslam_test::rng(109);
	double worst = 0;
	checkSmoothingJacobians(3, worst);
	core_test::reportWorst("smoothingResidual 3-dof", worst);
}

TEST(SmoothingJacobians, TwoDof)
{
	dynslam_test::rng(110);
	double worst = 0;
	checkSmoothingJacobians(2, worst);
	core_test::reportWorst("smoothingResidual 2-dof", worst);
}
