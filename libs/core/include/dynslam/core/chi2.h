#pragma once
/** @file chi2.h
 * Exact chi-square distribution function and quantiles: the gates of the estimators (JCBB's
 * joint compatibility, the classifier's tests) and the consistency bounds of the evaluation
 * (NEES, NIS; eval/chi2.h adds the bounds of an average over runs). Pure math, no MRPT.
 * The CDF is the regularized lower incomplete gamma function P(dof/2, x/2), evaluated by its
 * power series (x < a + 1) or its continued fraction (otherwise), to about 1e-14. Quantiles are
 * found by bisection on the CDF; no Wilson-Hilferty approximation (mrpt::math::chi2inv) is used:
 * it is off by 1e-2 at 2 dof. */

namespace dynslam
{
/** P(X <= x) for X ~ chi2(dof); dof > 0 (non-integer allowed). Throws std::invalid_argument
 * for dof <= 0 or NaN input. */
double chi2Cdf(double x, double dof);

/** The p-quantile of chi2(dof), 0 < p < 1, by bisection to a relative tolerance of 1e-13. */
double chi2Quantile(double p, double dof);

/** A two-sided interval [lower, upper]. */
struct TChi2Interval
{
	double lower = 0;
	double upper = 0;
	bool contains(double v) const { return v >= lower && v <= upper; }
};

/** Two-sided (confidence) interval of chi2(dof): [q((1-c)/2), q((1+c)/2)]. */
TChi2Interval chi2Interval(double dof, double confidence = 0.95);
}  // namespace dynslam
