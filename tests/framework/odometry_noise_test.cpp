/** The odometry noise is on the robot-frame increment and is rotated into the state:
 * Q = J_u S J_u^T, not S. Only an uneven, correlated S at a heading away from 0 and pi/2 can
 * show the difference (equal x/y variances without cross terms are rotation invariant). On an
 * odometry-only run every back-end's ego mean and covariance must equal MRPT's own pose
 * composition of Gaussians (CPosePDFGaussian::operator+=), step after step. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <iostream>

#include "any_backend.h"

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const char* kIni =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-4 1e-4]\n"
    "motion_noise = action\n"
    "initial_pose = [1 2 0.7]\n"
    "Sigma_0 = [1e-6 2e-6 1e-8]\n"
    "Sigma_xi = [0.1 0.1]\n"
    "[Framework]\n"
    "window_size = 3\n";

/** Uneven and correlated: 4e-4 along, 1e-4 across, correlated with each other and theta. */
Eigen::Matrix3d unevenS()
{
	Eigen::Matrix3d S;
	S << 4e-4, 1.5e-4, 2e-5, 1.5e-4, 1e-4, -1e-5, 2e-5, -1e-5, 1e-5;
	return S;
}

mrpt::math::CMatrixDouble33 toMrpt(const Eigen::Matrix3d& A)
{
	mrpt::math::CMatrixDouble33 M;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) M(i, j) = A(i, j);
	return M;
}
}  // namespace

TEST(OdometryNoise, RotatedIntoStateInEveryBackendAsMrptComposes)
{
	const Eigen::Matrix3d S = unevenS();
	const Eigen::Vector3d u(0.8, 0.1, 0.35);  // headings 0.7 .. 3.5 (across pi)
	const int steps = 9;
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		SCOPED_TRACE(kind);
		auto be = dynslam_test::anyBackend(kind, kIni);
		mrpt::poses::CPosePDFGaussian ref(
		    mrpt::poses::CPose2D(1, 2, 0.7),
		    toMrpt(Eigen::Vector3d(1e-6, 2e-6, 1e-8).asDiagonal().toDenseMatrix()));
		const mrpt::poses::CPosePDFGaussian inc(mrpt::poses::CPose2D(u[0], u[1], u[2]), toMrpt(S));
		double worstP = 0, worstX = 0, gap = 0;
		for (int k = 0; k < steps; ++k)
		{
			if (k > 0) ref += inc;
			be->processActionObservation(script::action(k == 0 ? Eigen::Vector3d::Zero() : u,
			                                            k == 0 ? Eigen::Matrix3d::Zero() : S),
			                             script::frame(Eigen::Vector3d::Zero(), {}));
			const auto p = be->getEgoPose();
			const Eigen::Matrix3d P = p.cov.asEigen(), Pr = ref.cov.asEigen();
			worstP = std::max(worstP, (P - Pr).cwiseAbs().maxCoeff() / Pr.cwiseAbs().maxCoeff());
			worstX = std::max(
			    worstX, std::abs(p.mean.x() - ref.mean.x()) + std::abs(p.mean.y() - ref.mean.y()) +
			                std::abs(mrpt::math::wrapToPi(p.mean.phi() - ref.mean.phi())));
			// What Q = S would give differs from the reference by this much (relative): the
			// test's power to see the difference.
			if (k == steps - 1)
			{
				Eigen::Matrix3d Jb;
				const double c = std::cos(ref.mean.phi() - u[2]),
				             s = std::sin(ref.mean.phi() - u[2]);
				Jb << c, -s, 0, s, c, 0, 0, 0, 1;
				gap =
				    (Jb * S * Jb.transpose() - S).cwiseAbs().maxCoeff() / Pr.cwiseAbs().maxCoeff();
			}
		}
		std::cout << "[odometry noise] " << kind << ": worst relative |P - P_mrpt| " << worstP
		          << ", |x - x_mrpt| " << worstX << " (one step of Q = S would be off by " << gap
		          << ")\n";
		EXPECT_LT(worstP, 1e-9);
		EXPECT_LT(worstX, 1e-9);
		EXPECT_GT(gap, 1e-3);  // the scenario can tell Q = S from J S J^T
	}
}
