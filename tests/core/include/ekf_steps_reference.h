#pragma once
/** Shared by the EKF step tests (test_ekf_steps*.cpp): the random test state (ego + 3 static
 * landmarks + one object with 3 features at time 0 and time t, n = 21), the trial headings,
 * error measures and dense reference computations of the paper's formulas. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core_test_utils.h"

namespace ekf_steps_test
{
using dynslam::ekf::RowMatrixXd;
using dynslam::models::wrapToPi;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;

inline constexpr double kTol = 1e-10;

/** max |A - B| / max(1, max |B|). */
inline double relErr(const MatrixXd& A, const MatrixXd& B)
{
	EXPECT_EQ(A.rows(), B.rows());
	EXPECT_EQ(A.cols(), B.cols());
	if (A.rows() != B.rows() || A.cols() != B.cols()) return 1e300;
	return (A - B).cwiseAbs().maxCoeff() / std::max(1.0, B.cwiseAbs().maxCoeff());
}

/** Symmetric to rounding and PSD (smallest eigenvalue >= -1e-12 * norm). */
inline ::testing::AssertionResult symmetricPsd(const MatrixXd& P)
{
	const double asym = (P - P.transpose()).norm(), nrm = P.norm();
	if (asym > 1e-14 * nrm)
		return ::testing::AssertionFailure() << "asymmetry " << asym << " (norm " << nrm << ")";
	const double lmin = core_test::minEigenvalue(P);
	if (lmin < -1e-12 * nrm)
		return ::testing::AssertionFailure()
		       << "smallest eigenvalue " << lmin << " (norm " << nrm << ")";
	return ::testing::AssertionSuccess();
}

/** State layout of the test scenario. */
inline constexpr int kN = 21;
inline constexpr int kL0 = 3;   // static landmarks at 3, 5, 7
inline constexpr int kF0 = 9;   // object features at time 0: 9, 11, 13
inline constexpr int kFt = 15;  // the same features at time t: 15, 17, 19

struct TScenario
{
	VectorXd x;
	RowMatrixXd P;
};

/** Random scenario: ego pose (heading in (-pi, pi] or at the wrap), landmarks, an object moved
 * by a random pose (dtheta possibly at the wrap) with small non-rigid noise. */
inline TScenario randomScenario(double egoHeading, double dtheta)
{
	TScenario s;
	s.x.resize(kN);
	s.x.head<3>() << uniform(-20, 20), uniform(-20, 20), egoHeading;
	s.x.segment(kL0, 6) = core_test::randomVector(6, -40, 40);
	const Eigen::Vector2d c(uniform(-30, 30), uniform(-30, 30));
	Eigen::Matrix2Xd f0(2, 3);
	// a well-spread triangle (radius 2-5 m) around c
	const double r = uniform(2, 5), phi = uniform(-M_PI, M_PI);
	for (int k = 0; k < 3; ++k)
		f0.col(k) = c + r * uniform(0.7, 1.0) *
		                    Eigen::Vector2d(std::cos(phi + 2.1 * k), std::sin(phi + 2.1 * k));
	const Eigen::Vector3d xi(uniform(-5, 5), uniform(-5, 5), dtheta);
	for (int k = 0; k < 3; ++k)
	{
		s.x.segment<2>(kF0 + 2 * k) = f0.col(k);
		s.x.segment<2>(kFt + 2 * k) = xi.head<2>() + c +
		                              dynslam::models::rot2(xi[2]) * (f0.col(k) - c) +
		                              core_test::randomVector(2, -0.05, 0.05);
	}
	s.P = core_test::randomSPD(kN, 0.5);
	return s;
}

/** Heading pairs for the trials: random ones, then the wrap. */
inline std::vector<std::pair<double, double>> trialAngles(int nRandom)
{
	std::vector<std::pair<double, double>> a;
	for (int i = 0; i < nRandom; ++i) a.emplace_back(uniform(-M_PI, M_PI), uniform(-M_PI, M_PI));
	for (double th : core_test::wrapHeadings()) a.emplace_back(th, -th);
	return a;
}

inline Eigen::Vector3d refCompose(const Eigen::Vector3d& x, const Eigen::Vector3d& u)
{
	return {x[0] + std::cos(x[2]) * u[0] - std::sin(x[2]) * u[1],
	        x[1] + std::sin(x[2]) * u[0] + std::cos(x[2]) * u[1], wrapToPi(x[2] + u[2])};
}

/** Textbook dense Kalman update with a full H: returns (x+, P+, NIS). */
struct TDense
{
	VectorXd x;
	MatrixXd P;
	double nis;
};
inline TDense denseUpdate(const VectorXd& x, const MatrixXd& P, const MatrixXd& H,
                          const VectorXd& nu, const MatrixXd& R)
{
	const MatrixXd S = H * P * H.transpose() + R;
	const MatrixXd Sinv = S.inverse();
	const MatrixXd K = P * H.transpose() * Sinv;
	const MatrixXd I = MatrixXd::Identity(x.size(), x.size());
	return {x + K * nu, (I - K * H) * P, nu.dot(Sinv * nu)};
}
}  // namespace ekf_steps_test
