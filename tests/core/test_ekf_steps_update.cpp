/** EKF steps of ekf_steps.h vs dense computations of the paper's formulas (continued from
 * test_ekf_steps.cpp, same random states and tolerances): the smoothing update, propagation,
 * kept indices and marginals, and bad input to the augmentations. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "core_test_utils.h"
#include "ekf_steps_reference.h"

using namespace dynslam;
using namespace ekf_steps_test;
using dynslam::models::MeasurementModel;

namespace
{
/** Paper's smoothing residual on poses of dimension d, re-implemented. */
VectorXd refSmoothing(const VectorXd& a, const VectorXd& b, const VectorXd& c)
{
	VectorXd s = (c - b) - (b - a);
	if (a.size() == 3) s[2] = wrapToPi(wrapToPi(c[2] - b[2]) - wrapToPi(b[2] - a[2]));
	return s;
}

void checkSmoothingUpdate(int d, double& worst, double& worstNis)
{
	// ego (3) + 2 landmarks (4) + three poses at scattered positions, then filler
	const int n = 3 + 4 + 3 * d + 2;
	const int ia = 3 + 4 + 2 * d, ib = 3 + 4, ic = 3 + 4 + d;  // not in time order
	for (const auto& [th0, w] : trialAngles(20))
	{
		VectorXd x = core_test::randomVector(n, -20, 20);
		x[2] = wrapToPi(th0);
		// poses with small random accelerations; headings around th0 (crossing the wrap)
		const VectorXd v = core_test::randomVector(d, -2, 2);
		x.segment(ia, d) = core_test::randomVector(d, -10, 10);
		x.segment(ib, d) = x.segment(ia, d) + v + core_test::randomVector(d, -0.3, 0.3);
		x.segment(ic, d) = x.segment(ib, d) + v + core_test::randomVector(d, -0.3, 0.3);
		if (d == 3)
		{
			x[ia + 2] = wrapToPi(th0);
			x[ib + 2] = wrapToPi(th0 + 0.1 * w);
			x[ic + 2] = wrapToPi(th0 + 0.25 * w);
		}
		RowMatrixXd P = core_test::randomSPD(n, 0.5);
		const MatrixXd Sigma_s = core_test::randomSPD(d, 0.05);

		// dense H of s over the whole state (numeric, angle output unwrapped)
		const core_test::VecFn sfun = [&](const VectorXd& w2)
		{ return refSmoothing(w2.segment(ia, d), w2.segment(ib, d), w2.segment(ic, d)); };
		std::vector<int> angleOut;
		if (d == 3) angleOut.push_back(2);
		const MatrixXd H = core_test::numericJacobianHO(sfun, x, angleOut);
		TDense ref = denseUpdate(x, P, H, -sfun(x), Sigma_s);
		if (d == 3)
			for (int base : {ia, ib, ic}) ref.x[base + 2] = wrapToPi(ref.x[base + 2]);

		VectorXd xs = x;
		const double nis = ekf::smoothingUpdate(xs, P, ia, ib, ic, Sigma_s);
		VectorXd dx = xs - ref.x;
		if (d == 3)
			for (int base : {ia, ib, ic})
			{
				dx[base + 2] = wrapToPi(dx[base + 2]);
				EXPECT_GT(xs[base + 2], -M_PI);
				EXPECT_LE(xs[base + 2], M_PI);
			}
		const double e =
		    std::max(dx.cwiseAbs().maxCoeff() / std::max(1.0, ref.x.cwiseAbs().maxCoeff()),
		             relErr(P, ref.P));
		EXPECT_LE(e, kTol) << "d = " << d << ", theta0 = " << th0;
		EXPECT_NEAR(nis, ref.nis, kTol * std::max(1.0, ref.nis));
		EXPECT_TRUE(symmetricPsd(P));
		worst = std::max(worst, e);
		worstNis = std::max(worstNis, std::abs(nis - ref.nis) / std::max(1.0, ref.nis));
		// the update reduces the residual
		EXPECT_LT(refSmoothing(xs.segment(ia, d), xs.segment(ib, d), xs.segment(ic, d)).norm(),
		          sfun(x).norm());
	}
}
}  // namespace

TEST(EkfSteps, SmoothingUpdateMatchesDense3Dof)
{
	dynslam_test::rng(505);
	double worst = 0, worstNis = 0;
	checkSmoothingUpdate(3, worst, worstNis);
	core_test::reportWorst("smoothingUpdate 3-dof x, P", worst);
	core_test::reportWorst("smoothingUpdate 3-dof NIS", worstNis);
}

TEST(EkfSteps, SmoothingUpdateMatchesDense2Dof)
{
	dynslam_test::rng(506);
	double worst = 0, worstNis = 0;
	checkSmoothingUpdate(2, worst, worstNis);
	core_test::reportWorst("smoothingUpdate 2-dof x, P", worst);
	core_test::reportWorst("smoothingUpdate 2-dof NIS", worstNis);
}

TEST(EkfSteps, SmoothingUpdateRejectsBadInput)
{
	dynslam_test::rng(510);
	TScenario s = randomScenario(0.1, 0.2);
	const VectorXd x0 = s.x;
	const MatrixXd S3 = 0.1 * MatrixXd::Identity(3, 3);
	EXPECT_THROW(ekf::smoothingUpdate(s.x, s.P, 3, 6, 9, 0.1 * MatrixXd::Identity(4, 4)),
	             std::invalid_argument);
	EXPECT_THROW(ekf::smoothingUpdate(s.x, s.P, 3, 6, 9, MatrixXd::Identity(3, 2)),
	             std::invalid_argument);
	EXPECT_THROW(ekf::smoothingUpdate(s.x, s.P, 3, 6, kN - 2, S3), std::out_of_range);
	EXPECT_THROW(ekf::smoothingUpdate(s.x, s.P, -1, 6, 9, S3), std::out_of_range);
	EXPECT_EQ(s.x, x0);
	// P must match x
	RowMatrixXd Psmall = s.P.topLeftCorner(kN - 1, kN - 1);
	EXPECT_THROW(ekf::smoothingUpdate(s.x, Psmall, 3, 6, 9, S3), std::invalid_argument);
}

TEST(EkfSteps, PropagateMatchesDense)
{
	dynslam_test::rng(507);
	double worst = 0;
	for (const auto& [heading, turn] : trialAngles(30))
	{
		const TScenario s = randomScenario(heading, 0.2);
		const Eigen::Vector3d u(uniform(-3, 3), uniform(-1, 1), 0.3 * turn);
		const MatrixXd Sigma_u = core_test::randomSPD(3, 0.01);
		const auto f = [&](const VectorXd& x, const Eigen::Vector3d& uu)
		{
			VectorXd out = x;
			out.head<3>() = refCompose(x.head<3>(), uu);
			return out;
		};
		const MatrixXd F =
		    core_test::numericJacobianHO([&](const VectorXd& x) { return f(x, u); }, s.x, {2});
		const MatrixXd G =
		    core_test::numericJacobianHO([&](const VectorXd& uu) { return f(s.x, uu); }, u, {2});
		const MatrixXd Pref = F * s.P * F.transpose() + G * Sigma_u * G.transpose();
		const VectorXd xref = f(s.x, u);

		VectorXd x = s.x;
		RowMatrixXd P = s.P;
		ekf::propagate(x, P, u, Sigma_u);
		VectorXd dx = x - xref;
		dx[2] = wrapToPi(dx[2]);
		EXPECT_GT(x[2], -M_PI);
		EXPECT_LE(x[2], M_PI);
		const double e = std::max(
		    dx.cwiseAbs().maxCoeff() / std::max(1.0, xref.cwiseAbs().maxCoeff()), relErr(P, Pref));
		EXPECT_LE(e, kTol) << "heading " << heading << ", u = " << u.transpose();
		EXPECT_TRUE(symmetricPsd(P));
		worst = std::max(worst, e);
	}
	core_test::reportWorst("propagate x, P", worst);
}

TEST(EkfSteps, KeptIndicesAndMarginal)
{
	EXPECT_EQ(ekf::keptIndices(6, {}), (std::vector<int>{0, 1, 2, 3, 4, 5}));
	EXPECT_EQ(ekf::keptIndices(6, {4, 1, 4}), (std::vector<int>{0, 2, 3, 5}));
	EXPECT_EQ(ekf::keptIndices(3, {0, 1, 2}), std::vector<int>{});
	EXPECT_EQ(ekf::keptIndices(0, {}), std::vector<int>{});
	EXPECT_THROW(ekf::keptIndices(6, {6}), std::out_of_range);
	EXPECT_THROW(ekf::keptIndices(6, {-1}), std::out_of_range);

	dynslam_test::rng(508);
	const RowMatrixXd P = core_test::randomSPD(8);
	const MatrixXd M = ekf::marginal(P, {5, 1, 2});
	ASSERT_EQ(M.rows(), 3);
	ASSERT_EQ(M.cols(), 3);
	const int idx[3] = {5, 1, 2};
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) EXPECT_EQ(M(i, j), P(idx[i], idx[j]));
	EXPECT_EQ(ekf::marginal(P, {}).size(), 0);
	EXPECT_THROW(ekf::marginal(P, {0, 8}), std::out_of_range);
	EXPECT_THROW(ekf::marginal(P, {-1}), std::out_of_range);
	// marginal of the kept indices = the covariance with the removed ones dropped
	const std::vector<int> keep = ekf::keptIndices(8, {0, 7});
	EXPECT_EQ(ekf::marginal(P, keep), MatrixXd(P.block(1, 1, 6, 6)));
}

TEST(EkfSteps, AugmentationRejectsBadInput)
{
	dynslam_test::rng(509);
	const TScenario s = randomScenario(0.1, 0.2);
	const Eigen::Matrix2d S = 0.01 * Eigen::Matrix2d::Identity();
	// gamma undetermined: one of three features seen
	EXPECT_THROW(ekf::objectPoseAugmentation(s.x, s.P, {kF0, kF0 + 2, kF0 + 4}, {kFt}, {0}, S),
	             std::domain_error);
	// no features
	EXPECT_THROW(ekf::objectPoseAugmentation(s.x, s.P, {}, {}, {}, S), std::invalid_argument);
	// a one-feature object seen twice at time t
	EXPECT_THROW(ekf::objectPoseAugmentation(s.x, s.P, {kF0}, {kFt, kFt + 2}, {}, S),
	             std::invalid_argument);
	// indices outside the state (the x-coordinate index of a 2-D feature must be <= n - 2)
	EXPECT_THROW(ekf::objectPoseAugmentation(s.x, s.P, {kF0, kN - 1}, {kFt, kFt + 2}, {}, S),
	             std::out_of_range);
	EXPECT_THROW(ekf::objectPoseAugmentation(s.x, s.P, {kF0, kF0 + 2}, {-2, kFt + 2}, {}, S),
	             std::out_of_range);
	// feature augmentation needs the 3 ego rows
	EXPECT_THROW(ekf::featureAugmentation(MeasurementModel::Cartesian, s.x.head<3>(),
	                                      s.P.topRows(2), {Eigen::Vector2d(1, 2)}, S),
	             std::invalid_argument);
	// no measurement: nothing to add
	const ekf::Augmentation a =
	    ekf::featureAugmentation(MeasurementModel::Cartesian, s.x.head<3>(), s.P.topRows(3), {}, S);
	EXPECT_EQ(a.mean.size(), 0);
	EXPECT_EQ(a.cov.size(), 0);
}
