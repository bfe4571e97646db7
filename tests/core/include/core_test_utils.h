#pragma once
/** Helpers shared by the dynslam::core tests: angle-aware numeric differentiation, a
 * high-order stencil for the dense EKF reference computations, and seeded random states. */
#include <dynslam/core/models/se2.h>
#include <dynslam_test/numeric_jacobian.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace core_test
{
using VecFn = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/** f with the output entries listed in angleOut unwrapped relative to f(x0): an angle that
 * jumps from +pi to -pi under a perturbation stays continuous, so differences of outputs
 * are differences of angles. */
inline VecFn unwrapAngles(const VecFn& f, const Eigen::VectorXd& x0, std::vector<int> angleOut)
{
	const Eigen::VectorXd nominal = f(x0);
	return [f, nominal, angleOut](const Eigen::VectorXd& x)
	{
		Eigen::VectorXd y = f(x);
		for (int i : angleOut) y[i] = nominal[i] + dynslam::models::wrapToPi(y[i] - nominal[i]);
		return y;
	};
}

/** Analytic J vs the central-difference Jacobian (h = 1e-6) of f with its angle outputs
 * unwrapped, at x: relative error (dynslam_test::relativeError) <= tol. The error is also
 * folded into `worst` so each test can report its worst case. */
inline ::testing::AssertionResult checkJacobian(const Eigen::MatrixXd& J, const VecFn& f,
                                                const Eigen::VectorXd& x,
                                                const std::vector<int>& angleOut, double& worst,
                                                double tol = 1e-6)
{
	const Eigen::MatrixXd J_num = dynslam_test::numericJacobian(unwrapAngles(f, x, angleOut), x);
	if (J_num.rows() != J.rows() || J_num.cols() != J.cols())
		return ::testing::AssertionFailure()
		       << "size mismatch: analytic " << J.rows() << "x" << J.cols() << " numeric "
		       << J_num.rows() << "x" << J_num.cols();
	const double e = dynslam_test::relativeError(J, J_num);
	worst = std::max(worst, e);
	if (e <= tol) return ::testing::AssertionSuccess();
	return ::testing::AssertionFailure() << "relative error " << e << " > " << tol
	                                     << " at x = " << x.transpose() << "\nanalytic:\n"
	                                     << J << "\nnumeric:\n"
	                                     << J_num;
}

/** Prints the worst error observed by a test (shown in the test log) and records it as a
 * test property (in --gtest_output=xml reports). */
inline void reportWorst(const char* what, double worst)
{
	std::printf("[  worst   ] %s: %.3g\n", what, worst);
	::testing::Test::RecordProperty(what, std::to_string(worst));
}

/** Sixth-order central-difference Jacobian (truncation O(h^6), rounding O(eps |f| / h)):
 * accurate to ~1e-12 for the smooth maps used here with h = 1e-2, so dense reference
 * computations built on it can be compared with the library at ~1e-10. Angle outputs listed
 * in angleOut are unwrapped relative to f(x). */
inline Eigen::MatrixXd numericJacobianHO(const VecFn& fIn, const Eigen::VectorXd& x,
                                         const std::vector<int>& angleOut = {}, double h = 1e-2)
{
	const VecFn f = unwrapAngles(fIn, x, angleOut);
	const Eigen::VectorXd f0 = f(x);
	Eigen::MatrixXd J(f0.size(), x.size());
	static const double w[3] = {45.0, -9.0, 1.0};
	for (int i = 0; i < x.size(); ++i)
	{
		Eigen::VectorXd acc = Eigen::VectorXd::Zero(f0.size());
		for (int k = 1; k <= 3; ++k)
		{
			Eigen::VectorXd xp = x, xm = x;
			xp[i] += k * h;
			xm[i] -= k * h;
			acc += w[k - 1] * (f(xp) - f(xm));
		}
		J.col(i) = acc / (60.0 * h);
	}
	return J;
}

/** Uniform random vector in [a, b]^n from the seeded test engine. */
inline Eigen::VectorXd randomVector(int n, double a, double b)
{
	Eigen::VectorXd v(n);
	for (int i = 0; i < n; ++i) v[i] = dynslam_test::uniform(a, b);
	return v;
}

/** Random pose: position in [-50, 50]^2, heading uniform in (-pi, pi]. */
inline Eigen::Vector3d randomPose()
{
	return {dynslam_test::uniform(-50, 50), dynslam_test::uniform(-50, 50),
	        dynslam::models::wrapToPi(dynslam_test::uniform(-M_PI, M_PI))};
}

/** Headings near the wrap: just below +pi, just above -pi, exactly pi, and -pi itself. */
inline std::vector<double> wrapHeadings()
{
	return {M_PI - 1e-9, -M_PI + 1e-9, M_PI, -M_PI, M_PI - 1e-6, -M_PI + 1e-6};
}

/** Dense random SPD matrix: A A^T + n * scale * I, A with entries in [-1, 1]. */
inline Eigen::MatrixXd randomSPD(int n, double scale = 1.0)
{
	Eigen::MatrixXd A(n, n);
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) A(i, j) = dynslam_test::uniform(-1, 1);
	Eigen::MatrixXd P = scale * (A * A.transpose() / n + 0.1 * Eigen::MatrixXd::Identity(n, n));
	return 0.5 * (P + P.transpose());
}

/** Smallest eigenvalue of the symmetric part of P. */
inline double minEigenvalue(const Eigen::MatrixXd& P)
{
	const Eigen::MatrixXd S = 0.5 * (P + P.transpose());
	return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly)
	    .eigenvalues()
	    .minCoeff();
}

/** vec() of a 2 x n feature matrix: (x1, y1, x2, y2, ...). */
inline Eigen::VectorXd vec(const Eigen::Matrix2Xd& F)
{
	return Eigen::Map<const Eigen::VectorXd>(F.data(), F.size());
}
inline Eigen::Matrix2Xd unvec(const Eigen::VectorXd& v)
{
	return Eigen::Map<const Eigen::Matrix2Xd>(v.data(), 2, v.size() / 2);
}

/** Random object: n features around a centre in [-30, 30]^2, spread radius in [1, 5]. */
inline Eigen::Matrix2Xd randomObject(int n)
{
	const Eigen::Vector2d c(dynslam_test::uniform(-30, 30), dynslam_test::uniform(-30, 30));
	const double r = dynslam_test::uniform(1, 5);
	Eigen::Matrix2Xd F(2, n);
	for (int k = 0; k < n; ++k)
		F.col(k) = c + Eigen::Vector2d(dynslam_test::uniform(-r, r), dynslam_test::uniform(-r, r));
	return F;
}
}  // namespace core_test
