#include <dynslam/core/chi2.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dynslam
{
namespace
{
/// Regularized lower incomplete gamma function P(a, x), a > 0, x >= 0.
double regularizedGammaP(double a, double x)
{
	if (x <= 0) return 0.0;
	const double logPrefactor = -x + a * std::log(x) - std::lgamma(a);
	constexpr double eps = 1e-16;
	if (x < a + 1.0)
	{
		// Series: P = e^{-x} x^a / Gamma(a) * sum_n x^n / (a (a+1) ... (a+n)).
		double term = 1.0 / a, sum = term;
		for (int n = 1; n < 100000; ++n)
		{
			term *= x / (a + n);
			sum += term;
			if (std::abs(term) < std::abs(sum) * eps) break;
		}
		return std::min(1.0, sum * std::exp(logPrefactor));
	}
	// Continued fraction for Q = 1 - P (modified Lentz).
	constexpr double tiny = 1e-300;
	double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
	for (int i = 1; i < 100000; ++i)
	{
		const double an = -i * (i - a);
		b += 2.0;
		d = an * d + b;
		if (std::abs(d) < tiny) d = tiny;
		c = b + an / c;
		if (std::abs(c) < tiny) c = tiny;
		d = 1.0 / d;
		const double del = d * c;
		h *= del;
		if (std::abs(del - 1.0) < eps) break;
	}
	return std::max(0.0, 1.0 - std::exp(logPrefactor) * h);
}

void checkDof(double dof)
{
	if (!(dof > 0) || !std::isfinite(dof))
		throw std::invalid_argument("chi2: degrees of freedom must be > 0, got " +
		                            std::to_string(dof));
}
}  // namespace

double chi2Cdf(double x, double dof)
{
	checkDof(dof);
	if (std::isnan(x)) throw std::invalid_argument("chi2Cdf: x is NaN");
	if (x == std::numeric_limits<double>::infinity()) return 1.0;
	return regularizedGammaP(0.5 * dof, 0.5 * x);
}

double chi2Quantile(double p, double dof)
{
	checkDof(dof);
	if (!(p > 0 && p < 1))
		throw std::invalid_argument("chi2Quantile: p must be in (0, 1), got " + std::to_string(p));
	double lo = 0, hi = dof + 10.0 * std::sqrt(2.0 * dof) + 10.0;
	while (chi2Cdf(hi, dof) < p) hi *= 2.0;
	for (int it = 0; it < 400 && (hi - lo) > 1e-13 * hi; ++it)
	{
		const double mid = 0.5 * (lo + hi);
		if (chi2Cdf(mid, dof) < p)
			lo = mid;
		else
			hi = mid;
	}
	return 0.5 * (lo + hi);
}

TChi2Interval chi2Interval(double dof, double confidence)
{
	if (!(confidence > 0 && confidence < 1))
		throw std::invalid_argument("chi2Interval: confidence must be in (0, 1), got " +
		                            std::to_string(confidence));
	const double alpha = 1.0 - confidence;
	return {chi2Quantile(0.5 * alpha, dof), chi2Quantile(1.0 - 0.5 * alpha, dof)};
}
}  // namespace dynslam
