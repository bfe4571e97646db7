/** Multiple-model prediction (models/mode_mixture.h, issue 28): the moment-matched mixture
 * applied by ekf::predictSubset equals the dense mixture of the M joint Gaussian predictions
 * (every entry of the state, cross terms included), also across the +-pi wrap of an angle;
 * Q_eff is PSD; the switching matrix, the mode posterior and the Gaussian log-likelihood
 * against independent computations; bad input. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>

#include "core_test_utils.h"

using namespace dynslam::models;
using dynslam::ekf::RowMatrixXd;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
/** Entries uniform in [-1, 1] from the seeded test engine (not Eigen's Random: std::rand). */
MatrixXd randomMatrix(int rows, int cols)
{
	MatrixXd A(rows, cols);
	for (int i = 0; i < rows; ++i)
		for (int j = 0; j < cols; ++j) A(i, j) = uniform(-1, 1);
	return A;
}

MatrixXd randomSpd(int n, double scale)
{
	MatrixXd A(n, n);
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) A(i, j) = uniform(-1, 1);
	return scale * (A * A.transpose() + 0.1 * MatrixXd::Identity(n, n));
}

/** The dense mixture: each mode's joint prediction of the whole state (x with idx replaced by
 * s_j, T_j = I with F_j on idx), then mean and covariance of the mixture (angle difference
 * wrapped at entry `angle` of the whole state). */
void denseMixture(const VectorXd& x, const MatrixXd& P, const std::vector<int>& idx,
                  const std::vector<VectorXd>& s_j, const std::vector<MatrixXd>& F_j,
                  const std::vector<MatrixXd>& Q_j, const VectorXd& w, int angle, VectorXd& x_out,
                  MatrixXd& P_out)
{
	const Eigen::Index n = x.size();
	std::vector<VectorXd> xs;
	std::vector<MatrixXd> Ps;
	for (size_t j = 0; j < s_j.size(); ++j)
	{
		MatrixXd T = MatrixXd::Identity(n, n);
		MatrixXd Qf = MatrixXd::Zero(n, n);
		for (size_t a = 0; a < idx.size(); ++a)
			for (size_t b = 0; b < idx.size(); ++b)
			{
				T(idx[a], idx[b]) = F_j[j](Eigen::Index(a), Eigen::Index(b));
				Qf(idx[a], idx[b]) = Q_j[j](Eigen::Index(a), Eigen::Index(b));
			}
		VectorXd xj = x;
		for (size_t a = 0; a < idx.size(); ++a) xj[idx[a]] = s_j[j][Eigen::Index(a)];
		xs.push_back(xj);
		Ps.push_back(T * P * T.transpose() + Qf);
	}
	// Mean: offsets from mode 0 (the angle's wrapped).
	VectorXd off = VectorXd::Zero(n);
	for (size_t j = 0; j < xs.size(); ++j)
	{
		VectorXd d = xs[j] - xs[0];
		if (angle >= 0) d[angle] = wrapToPi(d[angle]);
		off += w[Eigen::Index(j)] * d;
	}
	x_out = xs[0] + off;
	if (angle >= 0) x_out[angle] = wrapToPi(x_out[angle]);
	P_out = MatrixXd::Zero(n, n);
	for (size_t j = 0; j < xs.size(); ++j)
	{
		VectorXd d = xs[j] - x_out;
		if (angle >= 0) d[angle] = wrapToPi(d[angle]);
		P_out += w[Eigen::Index(j)] * (Ps[j] + d * d.transpose());
	}
}
}  // namespace

TEST(ModeMixture, PredictSubsetOfTheMixtureEqualsTheDenseMixture)
{
	dynslam_test::rng(2801);
	double worst = 0;
	for (int trial = 0; trial < 20; ++trial)
	{
		const int n = 15, M = 4;
		const std::vector<int> idx = {4, 5, 6, 11, 12, 13};  // [xi; v], the angle at 6
		VectorXd x(n);
		for (int i = 0; i < n; ++i) x[i] = uniform(-5, 5);
		// Every third trial: the object's heading at the wrap, modes on both sides of it.
		if (trial % 3 == 0) x[6] = M_PI - 1e-3;
		const MatrixXd P = randomSpd(n, 0.1);
		std::vector<VectorXd> s_j;
		std::vector<MatrixXd> F_j, Q_j;
		for (int j = 0; j < M; ++j)
		{
			MatrixXd F(6, 6);
			for (int a = 0; a < 6; ++a)
				for (int b = 0; b < 6; ++b) F(a, b) = uniform(-1, 1);
			VectorXd s = x(idx);
			for (int a = 0; a < 6; ++a) s[a] += uniform(-1, 1);
			s[2] = wrapToPi(x[6] + (trial % 3 == 0 ? uniform(0, 6e-3) : uniform(-0.5, 0.5)));
			s_j.push_back(s);
			F_j.push_back(F);
			Q_j.push_back(randomSpd(6, 0.01));
		}
		VectorXd w(M);
		for (int j = 0; j < M; ++j) w[j] = uniform(0.01, 1);
		w /= w.sum();
		const TModeMixture mix = mixModes(s_j, F_j, Q_j, w, P(idx, idx), 2);
		// Q_eff is symmetric PSD
		EXPECT_LT((mix.Q_eff - mix.Q_eff.transpose()).norm(), 1e-14);
		EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(mix.Q_eff).eigenvalues().minCoeff(),
		          -1e-12);
		VectorXd x_ref;
		MatrixXd P_ref;
		denseMixture(x, P, idx, s_j, F_j, Q_j, w, 6, x_ref, P_ref);
		VectorXd xs = x;
		RowMatrixXd Ps = P;
		dynslam::ekf::predictSubset(xs, Ps, idx, mix.s, mix.F, mix.Q_eff);
		VectorXd dx = xs - x_ref;
		dx[6] = wrapToPi(dx[6]);
		worst = std::max(
		    {worst, dx.cwiseAbs().maxCoeff(), (MatrixXd(Ps) - P_ref).cwiseAbs().maxCoeff()});
	}
	core_test::reportWorst("mixture vs dense", worst);
	EXPECT_LT(worst, 1e-10);
}

TEST(ModeMixture, OneModeWithAllTheWeightIsThatModesPrediction)
{
	dynslam_test::rng(2802);
	const MatrixXd P = randomSpd(4, 0.1);
	std::vector<VectorXd> s_j = {randomMatrix(4, 1), randomMatrix(4, 1)};
	std::vector<MatrixXd> F_j = {randomMatrix(4, 4), randomMatrix(4, 4)};
	std::vector<MatrixXd> Q_j = {randomSpd(4, 0.01), randomSpd(4, 0.01)};
	const TModeMixture mix = mixModes(s_j, F_j, Q_j, Eigen::Vector2d(0, 1), P);
	EXPECT_LT((mix.s - s_j[1]).norm(), 1e-15);
	EXPECT_LT((mix.F - F_j[1]).norm(), 1e-15);
	EXPECT_LT((mix.Q_eff - Q_j[1]).norm(), 1e-14);
}

TEST(ModeMixture, SwitchingPosteriorAndLikelihoodAgainstHandComputations)
{
	const MatrixXd Pi = uniformSwitching(4, 0.06);
	EXPECT_NEAR(Pi(0, 0), 0.94, 1e-15);
	EXPECT_NEAR(Pi(2, 1), 0.02, 1e-15);
	EXPECT_LT((Pi.rowwise().sum() - VectorXd::Ones(4)).norm(), 1e-15);
	const Eigen::Vector4d mu(0.1, 0.6, 0.2, 0.1), logL(-3.0, -1.0, -2.5, -40.0);
	const Eigen::Vector4d prior = Pi.transpose() * mu;
	Eigen::Vector4d ref;
	for (int j = 0; j < 4; ++j) ref[j] = prior[j] * std::exp(logL[j]);
	ref /= ref.sum();
	EXPECT_LT((modePosterior(mu, Pi, logL) - ref).norm(), 1e-15);
	EXPECT_LT((modePosterior(mu, Pi, VectorXd()) - prior).norm(), 1e-15);  // no readings
	// Likelihoods far below double's range: the log-sum-exp keeps their ratios.
	const Eigen::Vector4d tiny = logL.array() - 2000.0;
	EXPECT_LT((modePosterior(mu, Pi, tiny) - ref).norm(), 1e-12);
	const Eigen::Vector4d none = Eigen::Vector4d::Constant(-INFINITY);
	EXPECT_LT((modePosterior(mu, Pi, none) - prior).norm(), 1e-15);

	dynslam_test::rng(2803);
	const MatrixXd S = randomSpd(4, 1.0);
	const VectorXd nu = randomMatrix(4, 1);
	const double ref_ll = -0.5 * (nu.dot(S.inverse() * nu) + std::log(S.determinant()));
	EXPECT_NEAR(gaussianLogLikelihood(nu, S), ref_ll, 1e-12);
	EXPECT_THROW(gaussianLogLikelihood(nu, -S), std::runtime_error);
}

TEST(ModeMixture, ReadingsLikelihoodUnderAModesPredictionEqualsSequentialConditioning)
{
	// e = [ego (3); s (4); two f_0 (4)], three readings with their own noise. Independent of
	// the batch formula: the mode's prediction entry by entry, then log p(nu) by the chain rule,
	// one reading at a time (sequential Kalman conditioning of the prediction's error).
	dynslam_test::rng(2805);
	const int n = 11, off = 3, ns = 4, m = 3;
	const MatrixXd P_e = randomSpd(n, 0.5), Q = randomSpd(ns, 0.1);
	const MatrixXd F = MatrixXd::Identity(ns, ns) + 0.3 * randomMatrix(ns, ns);
	const MatrixXd H = randomMatrix(2 * m, n);
	const VectorXd nu = randomMatrix(2 * m, 1);
	MatrixXd R = MatrixXd::Zero(2 * m, 2 * m);
	for (int r = 0; r < m; ++r) R.block(2 * r, 2 * r, 2, 2) = randomSpd(2, 0.2);
	MatrixXd P = P_e;  // the prediction: rows, then columns of s through F
	for (int i = 0; i < n; ++i)
		P.row(i).segment(off, ns) = (F * P_e.row(i).segment(off, ns).transpose()).transpose();
	const MatrixXd Prow = P;
	for (int j = 0; j < n; ++j) P.col(j).segment(off, ns) = F * Prow.col(j).segment(off, ns);
	P.block(off, off, ns, ns) += Q;
	VectorXd delta = VectorXd::Zero(n);  // the conditional mean of the prediction's error
	double ll = 0;
	for (int r = 0; r < m; ++r)
	{
		const MatrixXd Hr = H.middleRows(2 * r, 2);
		const MatrixXd S = Hr * P * Hr.transpose() + R.block(2 * r, 2 * r, 2, 2);
		const VectorXd y = nu.segment(2 * r, 2) - Hr * delta;
		ll += -0.5 * (y.dot(S.inverse() * y) + std::log(S.determinant()));
		const MatrixXd K = P * Hr.transpose() * S.inverse();
		delta += K * y;
		P -= K * S * K.transpose();
	}
	EXPECT_NEAR(predictedReadingsLogLikelihood(P_e, off, F, Q, H, nu, R), ll, 1e-10);
	// Sizes: s beyond e, H's columns, R's size.
	EXPECT_THROW(predictedReadingsLogLikelihood(P_e, n - 2, F, Q, H, nu, R), std::invalid_argument);
	EXPECT_THROW(predictedReadingsLogLikelihood(P_e, off, F, Q, H.leftCols(n - 1), nu, R),
	             std::invalid_argument);
	EXPECT_THROW(predictedReadingsLogLikelihood(P_e, off, F, Q, H, nu, R.topLeftCorner(4, 4)),
	             std::invalid_argument);
}

TEST(ModeMixture, BadInputIsAClearError)
{
	const std::vector<VectorXd> s = {VectorXd::Zero(2)};
	const std::vector<MatrixXd> F = {MatrixXd::Identity(2, 2)}, Q = {MatrixXd::Identity(2, 2)};
	const MatrixXd P = MatrixXd::Identity(2, 2);
	EXPECT_THROW(mixModes(s, F, Q, Eigen::Vector2d(0.5, 0.5), P), std::invalid_argument);
	EXPECT_THROW(mixModes(s, F, Q, VectorXd::Constant(1, 0.9), P), std::invalid_argument);
	EXPECT_THROW(mixModes(s, F, Q, VectorXd::Ones(1), MatrixXd::Identity(3, 3)),
	             std::invalid_argument);
	EXPECT_THROW(mixModes({VectorXd::Zero(3)}, F, Q, VectorXd::Ones(1), P), std::invalid_argument);
	EXPECT_THROW(uniformSwitching(1, 0.1), std::invalid_argument);
	EXPECT_THROW(uniformSwitching(3, 1.0), std::invalid_argument);
	EXPECT_THROW(uniformSwitching(3, -0.1), std::invalid_argument);
	EXPECT_THROW(modePosterior(VectorXd::Ones(3) / 3, MatrixXd::Identity(2, 2), VectorXd()),
	             std::invalid_argument);
}
