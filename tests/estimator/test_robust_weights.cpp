/** The kernel weights of the robust update engine (robust_update_engines.h) with values by hand
 * (issue 32, "Test gaps to close"): the weight functions themselves on both sides of Huber's
 * corner c, and the engine's weight of a reading whose Mahalanobis residual length d is known in
 * closed form (the weight is a function of d, not of d^2).
 *
 * The scene: the ego at the origin with zero covariance, one landmark at (5, 0) with covariance
 * p I, a Cartesian reading with R = sigma^2 I (sigma = 0.1), innovation nu along x. Then
 * H = [J_z_x, I], S = (p + sigma^2 / w) I for weight w, and the residual after the update is
 * r = (sigma^2 / w) / (p + sigma^2 / w) nu, so d(w) = |r| / sigma = sigma |nu| / (w p + sigma^2).
 * After the plain update (w = 1): d_1 = 0.1 |nu| / (p + 0.01). */
#include <dynslam/estimator/robust_update_engines.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace dynslam;
using namespace dynslam::estimator;

TEST(RobustWeights, HuberOnBothSidesOfItsCornerAndCauchy)
{
	// Huber: 1 up to c, c / d beyond.
	EXPECT_EQ(robustWeight(RobustKernel::Huber, 0.0, 2.0), 1.0);
	EXPECT_EQ(robustWeight(RobustKernel::Huber, 1.99, 2.0), 1.0);
	EXPECT_EQ(robustWeight(RobustKernel::Huber, 2.0, 2.0), 1.0);
	EXPECT_NEAR(robustWeight(RobustKernel::Huber, 2.01, 2.0), 2.0 / 2.01, 1e-15);
	EXPECT_NEAR(robustWeight(RobustKernel::Huber, 4.0, 2.0), 0.5, 1e-15);
	EXPECT_NEAR(robustWeight(RobustKernel::Huber, 10.0, 1.5), 0.15, 1e-15);
	// Cauchy: 1 / (1 + (d / c)^2).
	EXPECT_EQ(robustWeight(RobustKernel::Cauchy, 0.0, 2.0), 1.0);
	EXPECT_NEAR(robustWeight(RobustKernel::Cauchy, 2.0, 2.0), 0.5, 1e-15);
	EXPECT_NEAR(robustWeight(RobustKernel::Cauchy, 4.0, 2.0), 0.2, 1e-15);
	EXPECT_NEAR(robustWeight(RobustKernel::Cauchy, 1.0, 4.0), 1 / 1.0625, 1e-15);
}

namespace
{
struct TOne
{
	Eigen::VectorXd x = Eigen::VectorXd::Zero(5);
	ekf::RowMatrixXd P = ekf::RowMatrixXd::Zero(5, 5);
	std::vector<TStaticObservation> obs;
	TUpdateContext ctx;
	/** Landmark covariance p I, innovation (nu, 0). */
	TOne(double p, double nu)
	{
		x << 0, 0, 0, 5, 0;
		P(3, 3) = P(4, 4) = p;
		ctx.R = 0.01 * Eigen::Matrix2d::Identity();
		obs.push_back({7, Eigen::Vector2d(5 + nu, 0), 3});
	}
};

/** The weight after the plain update (two updates: the second uses it). */
double firstWeight(RobustKernel k, double c, double p, double nu)
{
	TOne s(p, nu);
	CRobustUpdateEngine e(k, c, 2);
	e.update(s.x, s.P, s.obs, s.ctx);
	EXPECT_EQ(e.lastWeights().size(), 1u);
	return e.lastWeights().at(0);
}
}  // namespace

TEST(RobustWeights, EngineWeighsByTheMahalanobisLengthNotItsSquare)
{
	// p = 0.03: d_1 = 0.1 |nu| / 0.04 = 2.5 |nu|.
	// |nu| = 1.6: d_1 = 4; Huber c = 2: 0.5 (from d^2 = 16: 0.125); Cauchy c = 2: 1 / 5 = 0.2
	// (from d^2: 1 / 65).
	EXPECT_NEAR(firstWeight(RobustKernel::Huber, 2.0, 0.03, 1.6), 0.5, 1e-9);
	EXPECT_NEAR(firstWeight(RobustKernel::Cauchy, 2.0, 0.03, 1.6), 0.2, 1e-9);
	// Both sides of Huber's corner c = 2: d_1 = 1.9 (|nu| = 0.76): weight 1, converged after one
	// update (from d^2 = 3.61 it would be 0.554); d_1 = 2.1 (|nu| = 0.84): 2 / 2.1.
	{
		TOne s(0.03, 0.76);
		CRobustUpdateEngine e(RobustKernel::Huber, 2.0, 10);
		e.update(s.x, s.P, s.obs, s.ctx);
		EXPECT_EQ(e.lastWeights().at(0), 1.0);
		EXPECT_EQ(e.lastIterations(), 1);
	}
	EXPECT_NEAR(firstWeight(RobustKernel::Huber, 2.0, 0.03, 0.84), 2 / 2.1, 1e-9);
}

TEST(RobustWeights, EngineConvergesToTheHuberFixedPoint)
{
	// Iterated: w = c / d(w) = c (w p + sigma^2) / (sigma |nu|), the fixed point
	// w* = c sigma^2 / (sigma |nu| - c p) = 2 * 0.01 / (0.16 - 0.06) = 0.2 (d = 10 > c), reached
	// by the contraction w <- 0.375 w + 0.125.
	TOne s(0.03, 1.6);
	CRobustUpdateEngine e(RobustKernel::Huber, 2.0, 100);
	e.update(s.x, s.P, s.obs, s.ctx);
	EXPECT_NEAR(e.lastWeights().at(0), 0.2, 1e-8);
	EXPECT_LT(e.lastIterations(), 100);
	// The landmark's update with R / w*: gain p / (p + sigma^2 / w*) = 0.03 / 0.08.
	EXPECT_NEAR(s.x[3], 5 + 1.6 * 0.03 / 0.08, 1e-8);
	EXPECT_NEAR(s.x[4], 0, 1e-12);
}
