#pragma once
/** Helpers shared by the framework tests: random states and relative errors. */
#include <dynslam/framework/running_cost.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

namespace dynslam_test
{
/** max |A - B| / max |B| (the relative error used by every equivalence test). */
inline double relErr(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B)
{
	if (A.rows() != B.rows() || A.cols() != B.cols()) return 1e300;
	const double s = std::max(B.cwiseAbs().maxCoeff(), 1e-300);
	return (A - B).cwiseAbs().maxCoeff() / s;
}

/** Random symmetric positive-definite n x n matrix with eigenvalues in [lo, hi]. */
inline Eigen::MatrixXd randomSpd(std::mt19937& rng, int n, double lo, double hi)
{
	std::normal_distribution<double> N(0, 1);
	Eigen::MatrixXd A(n, n);
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) A(i, j) = N(rng);
	const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
	const Eigen::MatrixXd Q = qr.householderQ();
	std::uniform_real_distribution<double> U(std::log(lo), std::log(hi));
	Eigen::VectorXd ev(n);
	for (int i = 0; i < n; ++i) ev[i] = std::exp(U(rng));
	Eigen::MatrixXd P = Q * ev.asDiagonal() * Q.transpose();
	return 0.5 * (P + P.transpose());
}

/** A cost with the variables `keys` (values stacked in x) and one Gaussian prior N(x, P). */
inline dynslam::framework::CRunningCost costFromGaussian(
    const std::vector<dynslam::framework::TVarKey>& keys, const std::vector<int>& dims,
    const Eigen::VectorXd& x, const Eigen::MatrixXd& P)
{
	dynslam::framework::CRunningCost c;
	int off = 0;
	for (size_t i = 0; i < keys.size(); ++i)
	{
		c.addVariable(keys[i], x.segment(off, dims[i]));
		off += dims[i];
	}
	c.addTerm(dynslam::framework::CPriorTerm::fromCovariance(keys, dims, x, P));
	return c;
}
}  // namespace dynslam_test
