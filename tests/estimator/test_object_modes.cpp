/** estimator::readingsModeLogLikelihoods (object_modes.h): the stacking of an object's readings
 * for the mode likelihoods of object_model = mm, shared by the dynamic EKF and Alg. 1 (their
 * whole-run agreement is Alg1.WholeRunEquivalenceMultipleModel). Here: against a stacking by
 * hand with the columns named explicitly (ego, pose, velocity 0, f_0), each mode's pose handed to
 * the sighting, no readings, and the size errors. */
#include <dynslam/estimator/object_modes.h>
#include <gtest/gtest.h>

#include <random>

using namespace dynslam;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
MatrixXd randomMatrix(std::mt19937& g, Eigen::Index r, Eigen::Index c)
{
	std::uniform_real_distribution<double> U(-1, 1);
	MatrixXd A(r, c);
	for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = U(g);
	return A;
}

MatrixXd randomSpd(std::mt19937& g, Eigen::Index n, double floor)
{
	const MatrixXd A = randomMatrix(g, n, n);
	return A * A.transpose() + floor * MatrixXd::Identity(n, n);
}
}  // namespace

TEST(ObjectModes, ReadingsLikelihoodStacksTheSightingsOfEachModesPose)
{
	// e = [ego (3); s = [xi (3); v (3)]; f_0 of two features (4)]; two modes, two readings whose
	// sighting is linear in xi: nu_r = z_r - A_r xi, Jacobians (B_r, A_r, C_r).
	std::mt19937 g(2901);
	const Eigen::Index d = 3, ns = 6, nf = 4, n = 3 + ns + nf, m = 2;
	const MatrixXd P_e = randomSpd(g, n, 0.5);
	estimator::TModePredictions pred;
	for (int j = 0; j < 2; ++j)
	{
		pred.s.push_back(randomMatrix(g, ns, 1));
		pred.F.push_back(MatrixXd::Identity(ns, ns) + 0.2 * randomMatrix(g, ns, ns));
		pred.Q.push_back(randomSpd(g, ns, 0.1));
	}
	std::vector<MatrixXd> A, B, C;
	std::vector<Eigen::Vector2d> z;
	for (Eigen::Index r = 0; r < m; ++r)
	{
		A.push_back(randomMatrix(g, 2, d));
		B.push_back(randomMatrix(g, 2, 3));
		C.push_back(randomMatrix(g, 2, nf));
		z.push_back(randomMatrix(g, 2, 1));
	}
	const Eigen::Matrix2d Sv = randomSpd(g, 2, 0.2);
	const auto sighting = [&](Eigen::Index r, const VectorXd& xi)
	{
		estimator::TReadingSighting s;
		s.nu = z[size_t(r)] - A[size_t(r)] * xi;
		s.H_x = B[size_t(r)];
		s.H_xi = A[size_t(r)];
		s.H_f0 = C[size_t(r)];
		return s;
	};
	const VectorXd logL = estimator::readingsModeLogLikelihoods(pred, P_e, d, m, Sv, sighting);
	ASSERT_EQ(logL.size(), 2);
	for (int j = 0; j < 2; ++j)
	{
		MatrixXd H = MatrixXd::Zero(2 * m, n), R = MatrixXd::Zero(2 * m, 2 * m);
		VectorXd nu(2 * m);
		for (Eigen::Index r = 0; r < m; ++r)
		{
			H.block(2 * r, 0, 2, 3) = B[size_t(r)];
			H.block(2 * r, 3, 2, d) = A[size_t(r)];
			H.block(2 * r, 9, 2, nf) = C[size_t(r)];
			R.block(2 * r, 2 * r, 2, 2) = Sv;
			nu.segment(2 * r, 2) = z[size_t(r)] - A[size_t(r)] * pred.s[size_t(j)].head(d);
		}
		EXPECT_EQ(logL[j], models::predictedReadingsLogLikelihood(P_e, 3, pred.F[size_t(j)],
		                                                          pred.Q[size_t(j)], H, nu, R));
	}
	EXPECT_NE(logL[0], logL[1]);
	// No readings: no likelihoods (the probabilities follow the switching only).
	EXPECT_EQ(estimator::readingsModeLogLikelihoods(pred, P_e, d, 0, Sv, sighting).size(), 0);
	// Sizes: a sighting's Jacobian on the pose or on f_0 of the wrong width, P_e too small.
	const auto narrow = [&](Eigen::Index r, const VectorXd& xi)
	{
		estimator::TReadingSighting s = sighting(r, xi);
		s.H_xi = s.H_xi.leftCols(2).eval();
		return s;
	};
	EXPECT_THROW(estimator::readingsModeLogLikelihoods(pred, P_e, d, m, Sv, narrow),
	             std::invalid_argument);
	EXPECT_THROW(estimator::readingsModeLogLikelihoods(pred, P_e.topLeftCorner(n - 2, n - 2), d, m,
	                                                   Sv, sighting),
	             std::invalid_argument);
	EXPECT_THROW(
	    estimator::readingsModeLogLikelihoods(pred, P_e.topLeftCorner(8, 8), d, m, Sv, sighting),
	    std::invalid_argument);
}
