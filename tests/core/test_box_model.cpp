/** The oriented-box measurement model (models/box.h): every Jacobian against central
 * differences (relative error <= 1e-6) at 60 seeded random states and with the ego and object
 * headings at +-pi; the inverse as a round trip; the front/back ambiguity of the heading
 * residual on both sides of its pi/2 boundary. */
#include <dynslam/core/models/box.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam::models;
using core_test::checkJacobian;
using core_test::VecFn;
using dynslam_test::uniform;
using Eigen::VectorXd;

namespace
{
struct TState
{
	Eigen::Vector3d x, o;
	Eigen::Vector2d e;
};

/** Random states, then every combination of a wrap heading for the ego and for the object. */
std::vector<TState> states()
{
	std::vector<TState> s;
	for (int i = 0; i < 60; ++i)
		s.push_back({core_test::randomPose(),
		             core_test::randomPose(),
		             {uniform(0.5, 12), uniform(0.4, 3)}});
	for (double th : core_test::wrapHeadings())
		for (double ps : core_test::wrapHeadings())
			s.push_back({{uniform(-50, 50), uniform(-50, 50), th},
			             {uniform(-50, 50), uniform(-50, 50), ps},
			             {4.2, 1.8}});
	// the object's heading relative to the ego at the wrap: psi - theta = +-pi
	s.push_back({{1, 2, 0.3}, {5, -3, 0.3 + M_PI}, {4, 2}});
	s.push_back({{1, 2, -0.3}, {5, -3, -0.3 - M_PI}, {4, 2}});
	return s;
}
}  // namespace

TEST(BoxModel, ObserveJacobians)
{
	double worst = 0;
	for (const TState& s : states())
	{
		Matrix53d J_z_x, J_z_o;
		Matrix52d J_z_e;
		boxObserve(s.x, s.o, s.e, &J_z_x, &J_z_o, &J_z_e);
		const VecFn fx = [&](const VectorXd& v) -> VectorXd { return boxObserve(v, s.o, s.e); };
		const VecFn fo = [&](const VectorXd& v) -> VectorXd { return boxObserve(s.x, v, s.e); };
		const VecFn fe = [&](const VectorXd& v) -> VectorXd { return boxObserve(s.x, s.o, v); };
		EXPECT_TRUE(checkJacobian(J_z_x, fx, s.x, {2}, worst));
		EXPECT_TRUE(checkJacobian(J_z_o, fo, s.o, {2}, worst));
		EXPECT_TRUE(checkJacobian(J_z_e, fe, s.e, {2}, worst));
	}
	core_test::reportWorst("box observe", worst);
}

TEST(BoxModel, InverseJacobiansAndRoundTrip)
{
	double worst = 0;
	for (const TState& s : states())
	{
		const Vector5d z = boxObserve(s.x, s.o, s.e);
		Eigen::Matrix3d J_o_x;
		Eigen::Matrix<double, 3, 5> J_o_z;
		const Eigen::Vector3d o = boxInverse(s.x, z, &J_o_x, &J_o_z);
		EXPECT_NEAR((o.head<2>() - s.o.head<2>()).norm(), 0, 1e-9);
		EXPECT_NEAR(wrapToPi(o.z() - s.o.z()), 0, 1e-12);
		EXPECT_EQ(z.tail<2>(), s.e);
		const VecFn fx = [&](const VectorXd& v) -> VectorXd { return boxInverse(v, z); };
		const VecFn fz = [&](const VectorXd& v) -> VectorXd { return boxInverse(s.x, v); };
		EXPECT_TRUE(checkJacobian(J_o_x, fx, s.x, {2}, worst));
		EXPECT_TRUE(checkJacobian(J_o_z, fz, z, {2}, worst));
	}
	core_test::reportWorst("box inverse", worst);
}

TEST(BoxModel, ValuesByHand)
{
	// ego at (1, 2) facing +y; a box at (1, 7) heading +x, 4 x 2: 5 m ahead, heading -90 deg
	const Vector5d z = boxObserve({1, 2, M_PI / 2}, {1, 7, 0}, {4, 2});
	EXPECT_NEAR(z(0), 5, 1e-12);
	EXPECT_NEAR(z(1), 0, 1e-12);
	EXPECT_NEAR(z(2), -M_PI / 2, 1e-12);
	EXPECT_EQ(z(3), 4);
	EXPECT_EQ(z(4), 2);
}

TEST(BoxModel, HeadingResidualModuloPi)
{
	Vector5d zhat, z;
	zhat << 5, 1, 0.2, 4, 2;
	z = zhat;
	bool flipped = true;
	// a detection pointing to the box's back: phi + pi + 0.1 -> residual 0.1, flipped
	z(2) = wrapToPi(zhat(2) + M_PI + 0.1);
	EXPECT_NEAR(boxInnovation(z, zhat, &flipped)(2), 0.1, 1e-12);
	EXPECT_TRUE(flipped);
	// both sides of the boundary pi/2: 1.57 stays, 1.58 becomes 1.58 - pi
	z(2) = zhat(2) + 1.57;
	EXPECT_NEAR(boxInnovation(z, zhat, &flipped)(2), 1.57, 1e-12);
	EXPECT_FALSE(flipped);
	z(2) = zhat(2) + 1.58;
	EXPECT_NEAR(boxInnovation(z, zhat, &flipped)(2), 1.58 - M_PI, 1e-12);
	EXPECT_TRUE(flipped);
	z(2) = zhat(2) - 1.57;
	EXPECT_NEAR(boxInnovation(z, zhat, &flipped)(2), -1.57, 1e-12);
	EXPECT_FALSE(flipped);
	z(2) = zhat(2) - 1.58;
	EXPECT_NEAR(boxInnovation(z, zhat, &flipped)(2), M_PI - 1.58, 1e-12);
	EXPECT_TRUE(flipped);
	// across the +-pi wrap of the headings themselves: 3.1 vs -3.1 is 0.0832 apart
	zhat(2) = 3.1;
	z(2) = -3.1;
	EXPECT_NEAR(boxInnovation(z, zhat, &flipped)(2), 2 * M_PI - 6.2, 1e-12);
	EXPECT_FALSE(flipped);
	// the other components are plain differences
	z << 6, 0.5, 3.1, 4.5, 1.5;
	const Vector5d r = boxInnovation(z, zhat);
	EXPECT_NEAR(r(0), 1, 1e-12);
	EXPECT_NEAR(r(1), -0.5, 1e-12);
	EXPECT_NEAR(r(3), 0.5, 1e-12);
	EXPECT_NEAR(r(4), -0.5, 1e-12);
}
