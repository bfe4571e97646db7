/** The decision thresholds of the live-merge detector (live_merge.h) on both sides of their
 * boundaries, with literal samples and expected values computed by hand (issue 32, "Test gaps
 * to close"): the SPRT bound log((1 - beta) / alpha) with unequal rates, the drift (slope)
 * chi-square with 2 m dof, the velocity residual's chi-square with its own dof.
 *
 * The samples: window 5 (six observations at steps 0..5, the decision at the sixth), y_i the
 * pair's features with covariance S = 0.01 I. For y_i = y_0 + i b e_1 the weighted least-squares
 * slope is b e_1 exactly, Cov(slope) = S / sum (t_i - 2.5)^2 = 0.01 I / 17.5, so
 * drift_chi2 = 1750 b^2. Each increment delta (C = S_k + S_(k-1) = 0.02 I) adds, in m2 dims,
 *   (m2 / 2) log((0.02 + sigma^2) / 0.02) - 0.5 |delta|^2 (1 / 0.02 - 1 / (0.02 + sigma^2)). */
#include <dynslam/estimator/live_merge.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynslam::estimator;

namespace
{
/** Observes the six samples y_i = y0 + i slope e_1 of pair (0, 1); returns the last stats and
 * checks that no decision comes before the window is full. */
TLiveMergeStats observeLine(CLiveMergeDetector& d, const Eigen::VectorXd& y0, double slope,
                            double velChi2 = 0, int velDof = 0)
{
	TLiveMergeStats st;
	for (int i = 0; i <= 5; ++i)
	{
		TLiveMergeSample s;
		s.step = i;
		s.y = y0;
		s.y[0] += slope * i;
		s.S = 0.01 * Eigen::MatrixXd::Identity(y0.size(), y0.size());
		s.vel_chi2 = velChi2;
		s.vel_dof = velDof;
		st = d.observe(0, 1, s);
		if (i < 5)
		{
			EXPECT_FALSE(st.rigid) << "decided before the window was full, i = " << i;
		}
	}
	EXPECT_EQ(st.increments, 5);
	return st;
}

TLiveMergeParams params(double alpha, double beta, double motionStd)
{
	return TLiveMergeParams{5, alpha, beta, motionStd, 0.99};
}

/** The window's SPRT sum of 5 equal increments slope e_1 in `dims` dimensions. */
double llrOfLine(int dims, double slope, double spread2)
{
	return 5 * (dims / 2.0 * std::log((0.02 + spread2) / 0.02) -
	            0.5 * slope * slope * (1 / 0.02 - 1 / (0.02 + spread2)));
}
}  // namespace

// alpha = 1e-3, beta = 0.01: merge at log(0.99 / 0.001) = log 990 = 6.8977 (swapped rates:
// log(0.999 / 0.01) = 4.6042). A constant y (delta = 0): 5 log(1 + sigma^2 / 0.02).
// sigma^2 = 0.06: 5 log 4 = 6.9315 >= 6.8977: merge; sigma^2 = 0.058: 5 log 3.9 = 6.8048: not.
TEST(LiveMergeThresholds, SprtBoundWithUnequalErrorRates)
{
	const Eigen::VectorXd y0 = Eigen::Vector2d(1, 0.5);
	for (const double spread2 : {0.06, 0.058})
	{
		CLiveMergeDetector d(params(1e-3, 0.01, std::sqrt(spread2)));
		const TLiveMergeStats st = observeLine(d, y0, 0);
		EXPECT_NEAR(st.llr, 5 * std::log(1 + spread2 / 0.02), 1e-9);
		EXPECT_EQ(st.drift_chi2, 0.0);
		EXPECT_EQ(st.rigid, spread2 == 0.06) << "LLR " << st.llr << ", bound " << std::log(990.0);
	}
}

// One feature (y in 2 dims): the drift quantile has 2 dof, -2 log 0.01 = 9.2103 (1 dof: 6.63,
// 3 dof: 11.34). drift_chi2 = 9.0 merges, 9.45 does not; the SPRT sum (sigma = 0.5) is ~12.4,
// far above log 990.
TEST(LiveMergeThresholds, DriftChiSquareWithTwoDofPerFeature)
{
	const Eigen::VectorXd y0 = Eigen::Vector2d(1, 0.5);
	for (const double chi2 : {9.0, 9.45})
	{
		CLiveMergeDetector d(params(1e-3, 0.01, 0.5));
		const double b = std::sqrt(chi2 / 1750);
		const TLiveMergeStats st = observeLine(d, y0, b);
		EXPECT_NEAR(st.drift_chi2, chi2, 1e-9);
		EXPECT_NEAR(st.llr, llrOfLine(2, b, 0.25), 1e-9);
		EXPECT_GT(st.llr, std::log(990.0));
		EXPECT_EQ(st.rigid, chi2 == 9.0) << "drift chi2 " << chi2 << ", 2 dof";
	}
}

// Two features (y in 4 dims): 4 dof, quantile 13.28 (3 dof: 11.34, 5 dof: 15.09).
TEST(LiveMergeThresholds, DriftChiSquareWithFourDofForTwoFeatures)
{
	Eigen::VectorXd y0(4);
	y0 << 1, 0.5, 3, -1;
	for (const double chi2 : {13.0, 13.6})
	{
		CLiveMergeDetector d(params(1e-3, 0.01, 0.5));
		const double b = std::sqrt(chi2 / 1750);
		const TLiveMergeStats st = observeLine(d, y0, b);
		EXPECT_NEAR(st.drift_chi2, chi2, 1e-9);
		EXPECT_NEAR(st.llr, llrOfLine(4, b, 0.25), 1e-9);
		EXPECT_EQ(st.rigid, chi2 == 13.0) << "drift chi2 " << chi2 << ", 4 dof";
	}
}

// The velocity residual with 3 dof: quantile 11.34 at 0.99 (2 dof: 9.21, 4 dof: 13.28).
TEST(LiveMergeThresholds, VelocityChiSquareWithItsOwnDof)
{
	const Eigen::VectorXd y0 = Eigen::Vector2d(1, 0.5);
	for (const double vel : {11.2, 11.5})
	{
		CLiveMergeDetector d(params(1e-3, 0.01, 0.5));
		const TLiveMergeStats st = observeLine(d, y0, 0, vel, 3);
		EXPECT_EQ(st.rigid, vel == 11.2) << "velocity chi2 " << vel << ", 3 dof";
	}
}
