// Exact chi-square CDF and quantiles (used for every NEES/NIS bound).
#include <dynslam/eval/chi2.h>
#include <gtest/gtest.h>
#include <mrpt/math/distributions.h>

#include <cmath>

using namespace dynslam::eval;

TEST(Chi2, QuantilesMatchTables)
{
	// Reference values (MATLAB chi2inv / scipy.stats.chi2.ppf).
	EXPECT_NEAR(chi2Quantile(0.975, 2), 7.3778, 5e-5);
	EXPECT_NEAR(chi2Quantile(0.025, 2), 0.050636, 5e-6);
	EXPECT_NEAR(chi2Quantile(0.99, 2), 9.2103, 5e-5);
	EXPECT_NEAR(chi2Quantile(0.025, 75), 52.942, 5e-4);
	EXPECT_NEAR(chi2Quantile(0.975, 75), 100.839, 5e-4);
	EXPECT_NEAR(chi2Quantile(0.975, 3), 9.3484, 5e-5);
	EXPECT_NEAR(chi2Quantile(0.025, 3), 0.21580, 5e-5);
	// slamtb neesPlots.m: DOF 150 -> [117.985, 185.800], DOF 18 -> [8.231, 31.526].
	EXPECT_NEAR(chi2Quantile(0.025, 150), 117.985, 5e-3);
	EXPECT_NEAR(chi2Quantile(0.975, 150), 185.800, 5e-3);
	EXPECT_NEAR(chi2Quantile(0.025, 18), 8.231, 5e-3);
	EXPECT_NEAR(chi2Quantile(0.975, 18), 31.526, 5e-3);
}

TEST(Chi2, CdfClosedFormsAndInverse)
{
	// dof 2: CDF = 1 - exp(-x/2); dof 1: erf(sqrt(x/2)).
	for (double x : {0.01, 0.5, 2.0, 7.0, 30.0})
	{
		EXPECT_NEAR(chi2Cdf(x, 2), 1 - std::exp(-x / 2), 1e-14);
		EXPECT_NEAR(chi2Cdf(x, 1), std::erf(std::sqrt(x / 2)), 1e-13);
	}
	EXPECT_EQ(chi2Cdf(0.0, 3), 0.0);
	for (double dof : {1.0, 3.0, 10.0, 75.0, 2500.0, 7500.0})
		for (double p : {0.001, 0.025, 0.5, 0.975, 0.999})
			EXPECT_NEAR(chi2Cdf(chi2Quantile(p, dof), dof), p, 1e-11) << dof << " " << p;
}

TEST(Chi2, MoreAccurateThanMrptCdf)
{
	// mrpt::math::chi2CDF (2.5.8) is an approximation: it differs from the exact CDF by up to
	// 7e-3 (e.g. dof 1, x 0.3: 0.4091 vs erf(sqrt(0.15)) = 0.4161). Ours agrees with it to 1e-2
	// and with the closed form to 1e-13, which is why the bounds do not use MRPT's functions.
	for (unsigned dof : {1u, 2u, 3u, 6u, 40u, 75u})
		for (double x : {0.3, 1.0, 4.0, 12.0, 80.0})
			EXPECT_NEAR(chi2Cdf(x, dof), mrpt::math::chi2CDF(dof, x), 1e-2) << dof << " " << x;
	const double exact = std::erf(std::sqrt(0.15));
	EXPECT_NEAR(chi2Cdf(0.3, 1), exact, 1e-13);
	EXPECT_GT(std::abs(mrpt::math::chi2CDF(1, 0.3) - exact), 1e-3);
	// And MRPT's Wilson-Hilferty chi2inv is off by ~1e-2 at 2 dof.
	EXPECT_GT(std::abs(mrpt::math::chi2inv(0.99, 2) - chi2Quantile(0.99, 2)), 5e-3);
}

TEST(Chi2, AverageBoundsOfNRuns)
{
	// 25 runs of a 3-dof ego pose: N * mean ~ chi2(75).
	const TChi2Interval b = averageChi2Bounds(75, 25);
	EXPECT_NEAR(b.lower, 52.942 / 25, 2e-5);
	EXPECT_NEAR(b.upper, 100.839 / 25, 2e-5);
	EXPECT_TRUE(b.contains(3.0));
	EXPECT_FALSE(b.contains(4.5));
	const TChi2Interval one = chi2Interval(2);
	EXPECT_NEAR(one.upper, 7.3778, 5e-5);
}

TEST(Chi2, RejectsBadArguments)
{
	EXPECT_THROW(chi2Quantile(0.0, 2), std::invalid_argument);
	EXPECT_THROW(chi2Quantile(1.0, 2), std::invalid_argument);
	EXPECT_THROW(chi2Quantile(0.5, 0), std::invalid_argument);
	EXPECT_THROW(chi2Cdf(std::nan(""), 2), std::invalid_argument);
	EXPECT_THROW(averageChi2Bounds(6, 0), std::invalid_argument);
	EXPECT_THROW(chi2Interval(2, 1.5), std::invalid_argument);
}
