#pragma once
/** Numerical differentiation helpers shared by the Jacobian tests.
 *
 * Central differences on a vector function; the comparison is relative to the larger of
 * the two Jacobians' norms (absolute near zero), and reports both matrices on failure. */
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <functional>
#include <random>
#include <sstream>

namespace dynslam_test
{
/** Central-difference Jacobian of f at x, with step h. */
inline Eigen::MatrixXd numericJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
    double h = 1e-6)
{
	const Eigen::VectorXd f0 = f(x);
	Eigen::MatrixXd J(f0.size(), x.size());
	for (int i = 0; i < x.size(); ++i)
	{
		Eigen::VectorXd xp = x, xm = x;
		xp[i] += h;
		xm[i] -= h;
		J.col(i) = (f(xp) - f(xm)) / (2 * h);
	}
	return J;
}

/** Relative error ||A - B|| / max(1, ||B||) (Frobenius). */
inline double relativeError(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B)
{
	return (A - B).norm() / std::max(1.0, B.norm());
}

/** gtest assertion: analytic J agrees with the numeric Jacobian of f at x to tol. */
inline ::testing::AssertionResult jacobianMatches(
    const Eigen::MatrixXd& J_analytic,
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
    double tol = 1e-6, double h = 1e-6)
{
	const Eigen::MatrixXd J_num = numericJacobian(f, x, h);
	if (J_num.rows() != J_analytic.rows() || J_num.cols() != J_analytic.cols())
		return ::testing::AssertionFailure()
		       << "size mismatch: analytic " << J_analytic.rows() << "x" << J_analytic.cols()
		       << " numeric " << J_num.rows() << "x" << J_num.cols();
	const double e = relativeError(J_analytic, J_num);
	if (e <= tol) return ::testing::AssertionSuccess();
	std::ostringstream ss;
	ss << "relative error " << e << " > " << tol << "\nanalytic:\n"
	   << J_analytic << "\nnumeric:\n"
	   << J_num;
	return ::testing::AssertionFailure() << ss.str();
}

/** Seeded random engine for tests (every random source is seeded). */
inline std::mt19937& rng(unsigned seed = 0)
{
	static std::mt19937 g(12345u);
	if (seed) g.seed(seed);
	return g;
}
inline double uniform(double a, double b)
{
	return std::uniform_real_distribution<double>(a, b)(rng());
}
}  // namespace dynslam_test
