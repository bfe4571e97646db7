/** The odometry bias model (models/odometry_bias.h) and Alg. 7 with the bias block
 * (ekf::propagateWithBias): analytic Jacobians vs central differences at random states and at
 * the +-pi wrap; the covariance vs the dense Phi P Phi^T + Q with Phi from a high-order
 * numerical Jacobian of the whole-state transition; the zero-bias, zero-noise case vs
 * ekf::propagate; bad input. */
#include <dynslam/core/ekf_odometry_bias.h>
#include <dynslam/core/models/odometry_bias.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam;
using core_test::checkJacobian;
using core_test::VecFn;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using RowMatrixXd = ekf::RowMatrixXd;

namespace
{
std::vector<Eigen::Vector3d> testPoses()
{
	std::vector<Eigen::Vector3d> poses;
	for (int i = 0; i < 60; ++i) poses.push_back(core_test::randomPose());
	for (double th : core_test::wrapHeadings())
		poses.emplace_back(uniform(-50, 50), uniform(-50, 50), th);
	return poses;
}

/** The whole-state transition of propagateWithBias (mean only). */
VectorXd transition(const VectorXd& x, const Eigen::Vector3d& u, int bi, int d, double dt)
{
	VectorXd y = x;
	y.head<3>() = models::biasedMotion(x.head<3>(), x.segment(bi, d), u, dt);
	return y;
}
}  // namespace

TEST(OdometryBias, JacobiansMatchNumerical)
{
	dynslam_test::rng(1701);
	double worst = 0;
	int i = 0;
	for (const Eigen::Vector3d& x : testPoses())
	{
		for (int d : {1, 2})
		{
			const double dt = uniform(0.05, 1.0);
			Eigen::Vector3d u(uniform(-2, 2), uniform(-2, 2), uniform(-1, 1));
			// at the wrap: turns that cross +-pi
			if (i >= 60) u[2] = (i % 2 ? 1 : -1) * 1e-7;
			VectorXd b(d);
			b[0] = uniform(-0.1, 0.1);
			if (d == 2) b[1] = uniform(-0.1, 0.1);
			Eigen::Matrix3d J_out_x, J_out_u;
			MatrixXd J_out_b;
			models::biasedMotion(x, b, u, dt, &J_out_x, &J_out_b, &J_out_u);
			const VecFn fx = [&](const VectorXd& v)
			{ return VectorXd(models::biasedMotion(v, b, u, dt)); };
			const VecFn fb = [&](const VectorXd& v)
			{ return VectorXd(models::biasedMotion(x, v, u, dt)); };
			const VecFn fu = [&](const VectorXd& v)
			{ return VectorXd(models::biasedMotion(x, b, v, dt)); };
			EXPECT_TRUE(checkJacobian(J_out_x, fx, x, {2}, worst));
			EXPECT_TRUE(checkJacobian(J_out_b, fb, b, {2}, worst)) << "d = " << d;
			EXPECT_TRUE(checkJacobian(J_out_u, fu, u, {2}, worst));
		}
		++i;
	}
	core_test::reportWorst("biasedMotion", worst);
}

TEST(OdometryBias, CorrectedIncrementModel)
{
	// u' = ((1 - s) dx, (1 - s) dy, dtheta - b_w dt)
	const Eigen::Vector3d u(1.0, -0.5, 0.2);
	VectorXd b(2);
	b << 0.1, 0.05;
	const Eigen::Vector3d uc = models::correctedIncrement(u, b, 0.5);
	EXPECT_DOUBLE_EQ(uc[0], 0.95);
	EXPECT_DOUBLE_EQ(uc[1], -0.475);
	EXPECT_DOUBLE_EQ(uc[2], 0.15);
	EXPECT_THROW(models::correctedIncrement(u, VectorXd(3), 0.5), std::invalid_argument);
}

TEST(OdometryBias, PropagateMatchesDense)
{
	dynslam_test::rng(1702);
	double worst = 0;
	int i = 0;
	for (const Eigen::Vector3d& x0 : testPoses())
	{
		const int d = 1 + (i++ % 2);
		const int n = 3 + 2 + 4 + 2;  // ego, a landmark, the bias slot at 5, more entries
		const int bi = 5;
		VectorXd x = core_test::randomVector(n, -10, 10);
		x.head<3>() = x0;
		x[bi] = uniform(-0.05, 0.05);
		if (d == 2) x[bi + 1] = uniform(-0.05, 0.05);
		RowMatrixXd P = core_test::randomSPD(n, 0.1);
		const Eigen::Vector3d u(uniform(-2, 2), uniform(-2, 2), uniform(-0.5, 0.5));
		const Eigen::Matrix3d Su = core_test::randomSPD(3, 0.01);
		const double dt = uniform(0.1, 1.0);
		ekf::TOdometryBiasBlock blk;
		blk.index = bi;
		blk.dim = d;
		blk.q = Eigen::Vector2d(uniform(0, 1e-3), uniform(0, 1e-3));

		// dense reference: Phi from a numerical Jacobian of the whole-state transition
		const VecFn f = [&](const VectorXd& v) { return transition(v, u, bi, d, dt); };
		const MatrixXd Phi = core_test::numericJacobianHO(f, x, {2});
		const VectorXd xref = f(x);
		Eigen::Matrix3d G;
		models::biasedMotion(x.head<3>(), x.segment(bi, d), u, dt, nullptr, nullptr, &G);
		MatrixXd Q = MatrixXd::Zero(n, n);
		Q.topLeftCorner<3, 3>() = G * Su * G.transpose();
		for (int k = 0; k < d; ++k) Q(bi + k, bi + k) = blk.q[k] * dt;
		const MatrixXd Pref = Phi * MatrixXd(P) * Phi.transpose() + Q;

		ekf::propagateWithBias(x, P, u, Su, blk, dt);
		VectorXd dx = x - xref;
		dx[2] = models::wrapToPi(dx[2]);
		const double e = std::max(dx.cwiseAbs().maxCoeff(),
		                          (MatrixXd(P) - Pref).norm() / std::max(1.0, Pref.norm()));
		EXPECT_LE(e, 1e-9) << "heading " << x0[2] << " d " << d;
		EXPECT_EQ((MatrixXd(P) - MatrixXd(P).transpose()).cwiseAbs().maxCoeff(), 0.0);
		worst = std::max(worst, e);
	}
	core_test::reportWorst("propagateWithBias x, P", worst);
}

TEST(OdometryBias, ZeroBiasWithoutNoiseEqualsPropagate)
{
	// b = 0, q = 0, uncorrelated bias: the ego part equals ekf::propagate exactly.
	dynslam_test::rng(1703);
	const int n = 7, bi = 5;
	VectorXd x = core_test::randomVector(n, -10, 10);
	x[bi] = 0;
	x[bi + 1] = 0;
	RowMatrixXd P = core_test::randomSPD(n, 0.1);
	P.row(bi).setZero();
	P.col(bi).setZero();
	P(bi, bi) = 1e-2;
	VectorXd x2 = x;
	RowMatrixXd P2 = P;
	const Eigen::Vector3d u(1, 0.2, 0.1);
	const Eigen::Matrix3d Su = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
	ekf::TOdometryBiasBlock blk;
	blk.index = bi;
	blk.dim = 1;
	ekf::propagateWithBias(x, P, u, Su, blk, 0.0);
	ekf::propagate(x2, P2, u, Su);
	EXPECT_LE((x - x2).cwiseAbs().maxCoeff(), 1e-15);
	EXPECT_LE((MatrixXd(P) - MatrixXd(P2)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(OdometryBias, PropagateRejectsBadInput)
{
	VectorXd x = VectorXd::Zero(5);
	RowMatrixXd P = RowMatrixXd::Identity(5, 5);
	const Eigen::Vector3d u(1, 0, 0);
	const Eigen::Matrix3d Su = Eigen::Matrix3d::Identity() * 1e-3;
	ekf::TOdometryBiasBlock blk;
	blk.index = 3;
	blk.dim = 2;
	EXPECT_NO_THROW(ekf::propagateWithBias(x, P, u, Su, blk, 0.1));
	blk.index = 4;
	EXPECT_THROW(ekf::propagateWithBias(x, P, u, Su, blk, 0.1), std::out_of_range);
	blk.index = 2;
	EXPECT_THROW(ekf::propagateWithBias(x, P, u, Su, blk, 0.1), std::out_of_range);
	blk.index = 3;
	blk.dim = 3;
	EXPECT_THROW(ekf::propagateWithBias(x, P, u, Su, blk, 0.1), std::invalid_argument);
	blk.dim = 1;
	EXPECT_THROW(ekf::propagateWithBias(x, P, u, Su, blk, -0.1), std::invalid_argument);
	blk.q[0] = -1;
	EXPECT_THROW(ekf::propagateWithBias(x, P, u, Su, blk, 0.1), std::invalid_argument);
}
