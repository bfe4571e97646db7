/** Each EKF step of ekf_steps.h vs an independent dense computation of the paper's formulas
 * (Alg. 3-7) on small random states: ego + 3 static landmarks + one object with 3 features at
 * time 0 and time t (n = 21), dense random SPD covariance. The references re-implement the
 * models (no library model call) and differentiate them with a 6th-order stencil, so they
 * also check the library's analytic Jacobians. Mean and covariance agree to 1e-10, relative
 * to the largest entry (absolute below 1). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <numeric>

#include "core_test_utils.h"
#include "ekf_steps_reference.h"

using namespace dynslam;
using dynslam::ekf::RowMatrixXd;
using dynslam::models::MeasurementModel;
using dynslam::models::wrapToPi;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using namespace ekf_steps_test;

namespace
{
// --- independent re-implementations of the paper's models -----------------------------

Eigen::Vector2d refInverseObserve(MeasurementModel m, const Eigen::Vector3d& x,
                                  const Eigen::Vector2d& z)
{
	if (m == MeasurementModel::Cartesian)
		return {x[0] + std::cos(x[2]) * z[0] - std::sin(x[2]) * z[1],
		        x[1] + std::sin(x[2]) * z[0] + std::cos(x[2]) * z[1]};
	return {x[0] + z[0] * std::cos(x[2] + z[1]), x[1] + z[0] * std::sin(x[2] + z[1])};
}

/** gamma by the SVD (Kabsch) solution of min sum |R a_i + t - b_i|^2 (proper rotation), then
 * the rotation about the all-feature centroid c0: (dx, dy) = t + R c0 - c0. n == 1:
 * translation only. */
VectorXd refGamma(const Eigen::Matrix2Xd& f0, const Eigen::Matrix2Xd& ft,
                  const std::vector<int>& seen)
{
	if (f0.cols() == 1) return ft.col(0) - f0.col(0);
	const int m = int(ft.cols());
	Eigen::Matrix2Xd a(2, m);
	for (int i = 0; i < m; ++i) a.col(i) = f0.col(seen.empty() ? i : seen[i]);
	const Eigen::Vector2d abar = a.rowwise().mean(), bbar = ft.rowwise().mean();
	const Eigen::Matrix2d H = (a.colwise() - abar) * (ft.colwise() - bbar).transpose();
	const Eigen::JacobiSVD<Eigen::Matrix2d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
	Eigen::Matrix2d D = Eigen::Matrix2d::Identity();
	D(1, 1) = (svd.matrixV() * svd.matrixU().transpose()).determinant() > 0 ? 1 : -1;
	const Eigen::Matrix2d R = svd.matrixV() * D * svd.matrixU().transpose();
	const Eigen::Vector2d t = bbar - R * abar, c0 = f0.rowwise().mean();
	Eigen::Vector3d xi;
	xi.head<2>() = t + R * c0 - c0;
	xi[2] = std::atan2(R(1, 0), R(0, 0));
	return xi;
}

/** Assemble [P cross^T; cross cov] of an augmentation. */
MatrixXd augmented(const MatrixXd& P, const ekf::Augmentation& a)
{
	const Eigen::Index n = P.rows(), m = a.mean.size();
	MatrixXd Q(n + m, n + m);
	Q << P, a.cross.transpose(), a.cross, a.cov;
	return Q;
}
}  // namespace

TEST(EkfSteps, FeatureAugmentationMatchesDense)
{
	dynslam_test::rng(501);
	double worstMean = 0, worstCov = 0;
	for (MeasurementModel model : {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (const auto& [heading, bearing] : trialAngles(20))
		{
			const TScenario s = randomScenario(heading, 0.3);
			const int k = 3;
			std::vector<Eigen::Vector2d> z;
			for (int i = 0; i < k; ++i)
			{
				const double r = uniform(1, 40), b = i == 0 ? bearing : uniform(-M_PI, M_PI);
				z.push_back(models::fromRangeBearing(model, r, b));
			}
			const MatrixXd R = core_test::randomSPD(2, 0.01);
			const ekf::Augmentation a =
			    ekf::featureAugmentation(model, s.x.head<3>(), s.P.topRows(3), z, R);

			// y(x, z_1..k) = [x; l(x_ego, z_1); ...], J = dy/d[x; z], P_new = J blkdiag(P, R..R)
			// J^T
			VectorXd v(kN + 2 * k);
			v.head(kN) = s.x;
			for (int i = 0; i < k; ++i) v.segment<2>(kN + 2 * i) = z[size_t(i)];
			const core_test::VecFn y = [&](const VectorXd& w)
			{
				VectorXd out(kN + 2 * k);
				out.head(kN) = w.head(kN);
				for (int i = 0; i < k; ++i)
					out.segment<2>(kN + 2 * i) =
					    refInverseObserve(model, w.head<3>(), w.segment<2>(kN + 2 * i));
				return out;
			};
			const MatrixXd J = core_test::numericJacobianHO(y, v, {2});
			MatrixXd Pbig = MatrixXd::Zero(kN + 2 * k, kN + 2 * k);
			Pbig.topLeftCorner(kN, kN) = s.P;
			for (int i = 0; i < k; ++i) Pbig.block<2, 2>(kN + 2 * i, kN + 2 * i) = R;
			const MatrixXd Pnew = J * Pbig * J.transpose();
			const VectorXd ynew = y(v);

			const double em = relErr(a.mean, ynew.tail(2 * k));
			const double ec = std::max(relErr(a.cross, Pnew.bottomLeftCorner(2 * k, kN)),
			                           relErr(a.cov, Pnew.bottomRightCorner(2 * k, 2 * k)));
			EXPECT_LE(em, kTol) << models::toString(model);
			EXPECT_LE(ec, kTol) << models::toString(model) << ", heading " << heading;
			EXPECT_LE(relErr(Pnew.topLeftCorner(kN, kN), s.P), kTol);
			EXPECT_TRUE(symmetricPsd(augmented(s.P, a)));
			worstMean = std::max(worstMean, em);
			worstCov = std::max(worstCov, ec);
		}
	core_test::reportWorst("featureAugmentation mean", worstMean);
	core_test::reportWorst("featureAugmentation cov", worstCov);
}

namespace
{
struct TPoseAugCase
{
	std::vector<int> f0_idx, ft_idx, seen;
	const char* name;
};

void checkObjectPoseAugmentation(const TScenario& s, const TPoseAugCase& c, double& worstMean,
                                 double& worstCov)
{
	const int n = int(c.f0_idx.size()), m = int(c.ft_idx.size());
	const MatrixXd Sigma_xi = core_test::randomSPD(2, 0.01);
	const ekf::Augmentation a =
	    ekf::objectPoseAugmentation(s.x, s.P, c.f0_idx, c.ft_idx, c.seen, Sigma_xi);

	const auto features = [&](const VectorXd& w, const std::vector<int>& idx)
	{
		Eigen::Matrix2Xd F(2, idx.size());
		for (size_t i = 0; i < idx.size(); ++i) F.col(Eigen::Index(i)) = w.segment<2>(idx[i]);
		return F;
	};
	const int d = n == 1 ? 2 : 3;
	std::vector<int> angleOut;
	if (d == 3) angleOut.push_back(2);
	// full map y(x) = [x; gamma(f0(x), ft(x))] and its dense Jacobian
	const core_test::VecFn y = [&](const VectorXd& w)
	{
		VectorXd out(kN + d);
		out << w, refGamma(features(w, c.f0_idx), features(w, c.ft_idx), c.seen);
		return out;
	};
	std::vector<int> yAngles = {2};
	if (d == 3) yAngles.push_back(kN + 2);
	const MatrixXd J = core_test::numericJacobianHO(y, s.x, yAngles);
	// Gamma2 = d gamma / d vec(ft), numerically
	const Eigen::Matrix2Xd ft = features(s.x, c.ft_idx), f0 = features(s.x, c.f0_idx);
	const MatrixXd Gamma2 = core_test::numericJacobianHO(
	    [&](const VectorXd& v) { return refGamma(f0, core_test::unvec(v), c.seen); },
	    core_test::vec(ft), angleOut);
	MatrixXd Pnew = J * s.P * J.transpose();
	MatrixXd SigmaBlk = MatrixXd::Zero(2 * m, 2 * m);
	for (int i = 0; i < m; ++i) SigmaBlk.block<2, 2>(2 * i, 2 * i) = Sigma_xi;
	Pnew.bottomRightCorner(d, d) += Gamma2 * SigmaBlk * Gamma2.transpose();

	const VectorXd ref = y(s.x).tail(d);
	ASSERT_EQ(a.mean.size(), d) << c.name;
	VectorXd diff = a.mean - ref;
	if (d == 3) diff[2] = wrapToPi(diff[2]);
	const double em = diff.cwiseAbs().maxCoeff() / std::max(1.0, ref.cwiseAbs().maxCoeff());
	const double ec = std::max(relErr(a.cross, Pnew.bottomLeftCorner(d, kN)),
	                           relErr(a.cov, Pnew.bottomRightCorner(d, d)));
	EXPECT_LE(em, kTol) << c.name << ": " << a.mean.transpose() << " vs " << ref.transpose();
	EXPECT_LE(ec, kTol) << c.name;
	EXPECT_TRUE(symmetricPsd(augmented(s.P, a))) << c.name;
	if (d == 3)
	{
		EXPECT_GT(a.mean[2], -M_PI);
		EXPECT_LE(a.mean[2], M_PI);
	}
	worstMean = std::max(worstMean, em);
	worstCov = std::max(worstCov, ec);
}
}  // namespace

TEST(EkfSteps, ObjectPoseAugmentationMatchesDense)
{
	dynslam_test::rng(502);
	const std::vector<TPoseAugCase> cases = {
	    {{kF0, kF0 + 2, kF0 + 4}, {kFt, kFt + 2, kFt + 4}, {}, "n = 3, all seen"},
	    {{kF0, kF0 + 2, kF0 + 4}, {kFt + 4, kFt}, {2, 0}, "n = 3, features 2 and 0 seen"},
	    {{kF0, kF0 + 2, kF0 + 4}, {kFt + 2, kFt + 4}, {1, 2}, "n = 3, features 1 and 2 seen"},
	    {{kF0 + 2}, {kFt + 2}, {}, "n = 1, translation only"}};
	double worstMean = 0, worstCov = 0;
	for (const auto& [heading, dtheta] : trialAngles(20))
	{
		const TScenario s = randomScenario(heading, dtheta);
		for (const TPoseAugCase& c : cases) checkObjectPoseAugmentation(s, c, worstMean, worstCov);
	}
	core_test::reportWorst("objectPoseAugmentation mean", worstMean);
	core_test::reportWorst("objectPoseAugmentation cov", worstCov);
}

TEST(EkfSteps, SparseUpdateMatchesDense)
{
	dynslam_test::rng(503);
	double worst = 0, worstNis = 0;
	for (int trial = 0; trial < 30; ++trial)
	{
		TScenario s = randomScenario(uniform(-M_PI, M_PI), 0.2);
		const int m = 1 + trial % 4, q = 2 + trial % 6;
		std::vector<int> perm(kN);
		std::iota(perm.begin(), perm.end(), 0);
		std::shuffle(perm.begin(), perm.end(), dynslam_test::rng());
		const std::vector<int> idx(perm.begin(), perm.begin() + q);  // random order
		const MatrixXd H = core_test::randomVector(m * q, -2, 2).reshaped(m, q);
		const VectorXd nu = core_test::randomVector(m, -1, 1);
		const MatrixXd R = core_test::randomSPD(m, 0.1);

		MatrixXd Hfull = MatrixXd::Zero(m, kN);
		for (int j = 0; j < q; ++j) Hfull.col(idx[size_t(j)]) = H.col(j);
		const TDense ref = denseUpdate(s.x, s.P, Hfull, nu, R);

		const double nis = ekf::sparseUpdate(s.x, s.P, idx, H, nu, R);
		const double e = std::max(relErr(s.x, ref.x), relErr(s.P, ref.P));
		EXPECT_LE(e, kTol) << "m = " << m << ", |idx| = " << q;
		EXPECT_NEAR(nis, ref.nis, kTol * std::max(1.0, ref.nis));
		EXPECT_TRUE(s.P.isApprox(s.P.transpose(), 0.0)) << "P not exactly symmetric";
		EXPECT_TRUE(symmetricPsd(s.P));
		worst = std::max(worst, e);
		worstNis = std::max(worstNis, std::abs(nis - ref.nis) / std::max(1.0, ref.nis));
	}
	core_test::reportWorst("sparseUpdate x, P", worst);
	core_test::reportWorst("sparseUpdate NIS", worstNis);
}

TEST(EkfSteps, SparseUpdateRejectsBadInput)
{
	dynslam_test::rng(504);
	TScenario s = randomScenario(0.1, 0.2);
	const std::vector<int> idx = {0, 4, 9};
	const MatrixXd H = core_test::randomVector(6, -1, 1).reshaped(2, 3);
	const VectorXd nu = VectorXd::Ones(2);
	const VectorXd x0 = s.x;
	// S not positive definite
	EXPECT_THROW(ekf::sparseUpdate(s.x, s.P, idx, H, nu, -100 * MatrixXd::Identity(2, 2)),
	             std::runtime_error);
	// inconsistent sizes
	EXPECT_THROW(ekf::sparseUpdate(s.x, s.P, {0, 4}, H, nu, MatrixXd::Identity(2, 2)),
	             std::invalid_argument);
	EXPECT_THROW(ekf::sparseUpdate(s.x, s.P, idx, H, VectorXd::Ones(3), MatrixXd::Identity(2, 2)),
	             std::invalid_argument);
	EXPECT_THROW(ekf::sparseUpdate(s.x, s.P, idx, H, nu, MatrixXd::Identity(3, 3)),
	             std::invalid_argument);
	// state index out of range
	EXPECT_THROW(ekf::sparseUpdate(s.x, s.P, {0, 4, kN}, H, nu, MatrixXd::Identity(2, 2)),
	             std::out_of_range);
	EXPECT_THROW(ekf::sparseUpdate(s.x, s.P, {0, -1, 3}, H, nu, MatrixXd::Identity(2, 2)),
	             std::out_of_range);
	EXPECT_EQ(s.x, x0) << "a rejected update changed the state";
	// an empty measurement changes nothing
	const RowMatrixXd P0 = s.P;
	EXPECT_EQ(ekf::sparseUpdate(s.x, s.P, {}, MatrixXd(0, 0), VectorXd(0), MatrixXd(0, 0)), 0.0);
	EXPECT_EQ(s.x, x0);
	EXPECT_EQ(s.P, P0);
}
