/** Theorems 4.1, 4.2 and A.1-A.5: each step of Alg. 1 (a Gauss-Newton or marginalization step
 * on the running cost) equals the matching step of the standard dynamic EKF (ekf_steps.h), on
 * small random states; mean and covariance within 1e-9 relative (max |A-B| / max |B|). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/framework/running_cost.h>
#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "framework_test_utils.h"

using namespace dynslam::framework;
using dynslam::ekf::RowMatrixXd;
using dynslam::models::MeasurementModel;
using dynslam_test::relErr;

namespace
{
constexpr double kTol = 1e-9;

/** A random dynamic-EKF state: ego, 3 landmarks, object 0 (3 features at time 0 and time 5),
 * object 1 (one feature, translation-only), poses xi of object 0 at 3, 4, 5 and of object 2
 * (translation-only) at 3, 4, 5. */
struct TRandomState
{
	std::vector<TVarKey> keys;
	std::vector<int> dims;
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	std::map<TVarKey, int> idx;  // state index of each block

	void add(const TVarKey& k, const Eigen::VectorXd& v)
	{
		idx[k] = int(x.size());
		keys.push_back(k);
		dims.push_back(int(v.size()));
		Eigen::VectorXd y(x.size() + v.size());
		y << x, v;
		x = y;
	}
	CRunningCost cost() const { return dynslam_test::costFromGaussian(keys, dims, x, P); }
};

TRandomState randomState(unsigned seed, double eigLo = 1e-4, double eigHi = 1e-1)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> N(0, 1);
	TRandomState s;
	s.x.resize(0);
	s.add(TVarKey::ego(5), Eigen::Vector3d(1 + N(rng), 2 + N(rng), 0.3 * N(rng)));
	for (int l = 10; l < 13; ++l)
		s.add(TVarKey::landmark(l), Eigen::Vector2d(5 * N(rng), 5 * N(rng)));
	Eigen::Matrix2Xd f0(2, 3);
	f0 << 8, 9.5, 8.2, 1, 1.3, 2.4;
	const Eigen::Vector3d xi(1 + 0.1 * N(rng), 0.5 + 0.1 * N(rng), 0.2 + 0.05 * N(rng));
	const Eigen::Matrix2Xd ft = dynslam::models::objectPoseMap(xi, f0);
	for (int k = 0; k < 3; ++k) s.add(TVarKey::objectFeature(0, k, 0), f0.col(k));
	for (int k = 0; k < 3; ++k)
		s.add(TVarKey::objectFeature(0, k, 5), ft.col(k) + 0.05 * Eigen::Vector2d(N(rng), N(rng)));
	s.add(TVarKey::objectFeature(1, 0, 0), Eigen::Vector2d(-4, 3));
	s.add(TVarKey::objectFeature(1, 0, 5), Eigen::Vector2d(-3.2, 3.5));
	for (int t = 3; t < 6; ++t)
		s.add(TVarKey::objectPose(0, t),
		      Eigen::Vector3d(0.3 * t + 0.1 * N(rng), 0.1 * t + 0.1 * N(rng),
		                      0.05 * t + 0.02 * N(rng)));
	for (int t = 3; t < 6; ++t)
		s.add(TVarKey::objectPose(2, t), Eigen::Vector2d(0.2 * t + 0.1 * N(rng), 0.1 * N(rng)));
	s.P = dynslam_test::randomSpd(rng, int(s.x.size()), eigLo, eigHi);
	return s;
}

/** Appends an EKF augmentation to (x, P). */
void append(Eigen::VectorXd& x, Eigen::MatrixXd& P, const dynslam::ekf::Augmentation& a)
{
	const Eigen::Index n = x.size(), m = a.mean.size();
	Eigen::VectorXd x2(n + m);
	x2 << x, a.mean;
	Eigen::MatrixXd P2(n + m, n + m);
	P2 << P, a.cross.transpose(), a.cross, a.cov;
	x = x2;
	P = P2;
}

/** Records and checks the relative errors of a step. */
void expectEqual(const char* what, const Eigen::VectorXd& xf, const Eigen::MatrixXd& Pf,
                 const Eigen::VectorXd& xe, const Eigen::MatrixXd& Pe)
{
	const double em = relErr(xf, xe), ec = relErr(Pf, Pe);
	std::cout << "[equivalence] " << what << ": mean " << em << ", covariance " << ec << "\n";
	EXPECT_LT(em, kTol) << what;
	EXPECT_LT(ec, kTol) << what;
}
}  // namespace

// Theorem A.1: feature augmentation (Alg. 3) = GN on prior + measurement residuals of the new
// features, linearized at (mu, l(x, z)).
TEST(StepEquivalence, FeatureAugmentationEquivalenceTheoremA1)
{
	for (auto model : {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (unsigned seed : {1u, 2u, 3u})
		{
			const TRandomState s = randomState(seed);
			const Eigen::Matrix2d R =
			    model == MeasurementModel::Cartesian
			        ? Eigen::Matrix2d(Eigen::Vector2d(1e-3, 2e-3).asDiagonal())
			        : Eigen::Matrix2d(Eigen::Vector2d(1e-3, 1e-5).asDiagonal());
			const std::vector<Eigen::Vector2d> z =
			    model == MeasurementModel::Cartesian
			        ? std::vector<Eigen::Vector2d>{{3, 1}, {-2, 4}}
			        : std::vector<Eigen::Vector2d>{{5, 0.3}, {7, -2.5}};
			CRunningCost c = s.cost();
			const Eigen::Vector3d ego = s.x.head<3>();
			for (size_t i = 0; i < z.size(); ++i)
			{
				const TVarKey k = TVarKey::landmark(int32_t(20 + i));
				c.addVariable(k, dynslam::models::inverseObserve(model, ego, z[i]));
				c.addTerm(std::make_shared<CMeasurementTerm>(5, k, z[i], model, R));
			}
			const auto r = c.gaussNewtonStep();

			Eigen::VectorXd xe = s.x;
			Eigen::MatrixXd Pe = s.P;
			append(
			    xe, Pe,
			    dynslam::ekf::featureAugmentation(model, ego, RowMatrixXd(s.P.topRows(3)), z, R));
			expectEqual("A.1 feature augmentation", c.stackedValues(), r.covariance, xe, Pe);
		}
}

// Theorems 4.1 / A.2: object-pose augmentation (Alg. 4) = GN on prior + the pose-space residual
// xi - gamma(f0, ft) with covariance Gamma2 diag(Sigma_xi) Gamma2^T.
TEST(StepEquivalence, ObjectPoseAugmentationEquivalenceTheorem41)
{
	const Eigen::Matrix2d Sxi = Eigen::Matrix2d::Identity() * 0.1;
	struct TCase
	{
		int obj;
		std::vector<int> seen;
	};
	for (const TCase& tc : {TCase{0, {0, 1, 2}}, TCase{0, {0, 2}}, TCase{1, {0}}})
		for (unsigned seed : {4u, 5u})
		{
			const TRandomState s = randomState(seed);
			const int n = tc.obj == 0 ? 3 : 1;
			TObjectPoseKeys k;
			k.pose = TVarKey::objectPose(tc.obj, 6);
			for (int j = 0; j < n; ++j) k.f0.push_back(TVarKey::objectFeature(tc.obj, j, 0));
			for (int j : tc.seen) k.ft.push_back(TVarKey::objectFeature(tc.obj, j, 5));
			k.seen = tc.seen;
			std::vector<int> f0_idx, ft_idx;
			for (const auto& key : k.f0) f0_idx.push_back(s.idx.at(key));
			for (const auto& key : k.ft) ft_idx.push_back(s.idx.at(key));
			const auto aug = dynslam::ekf::objectPoseAugmentation(s.x, RowMatrixXd(s.P), f0_idx,
			                                                      ft_idx, tc.seen, Sxi);

			CRunningCost c = s.cost();
			c.addVariable(k.pose, aug.mean);  // gamma(f0, ft): the linearization point of Alg. 1
			c.addTerm(std::make_shared<CObjectPosePoseTerm>(k, Sxi));
			const auto r = c.gaussNewtonStep();
			Eigen::VectorXd xe = s.x;
			Eigen::MatrixXd Pe = s.P;
			append(xe, Pe, aug);
			expectEqual("4.1 object pose augmentation (pose space)", c.stackedValues(),
			            r.covariance, xe, Pe);
		}
}

// The paper's feature-space residual f_t - g^o(xi, f_0): equal to Alg. 4 for one-feature
// (translation-only) objects, different for n >= 2 (it adds rigidity information on f_0, f_t).
TEST(StepEquivalence, FeatureSpaceObjectPoseResidualEquivalenceOnlyForOneFeature)
{
	const Eigen::Matrix2d Sxi = Eigen::Matrix2d::Identity() * 0.1;
	double worstOneFeature = 0, smallestRigid = 1e300;
	for (unsigned seed : {6u, 7u, 8u})
	{
		const TRandomState s = randomState(seed);
		for (int obj : {1, 0})
		{
			const int n = obj == 0 ? 3 : 1;
			TObjectPoseKeys k;
			k.pose = TVarKey::objectPose(obj, 6);
			std::vector<int> f0_idx, ft_idx;
			for (int j = 0; j < n; ++j)
			{
				k.f0.push_back(TVarKey::objectFeature(obj, j, 0));
				k.ft.push_back(TVarKey::objectFeature(obj, j, 5));
				k.seen.push_back(j);
				f0_idx.push_back(s.idx.at(k.f0.back()));
				ft_idx.push_back(s.idx.at(k.ft.back()));
			}
			const auto aug = dynslam::ekf::objectPoseAugmentation(s.x, RowMatrixXd(s.P), f0_idx,
			                                                      ft_idx, k.seen, Sxi);
			CRunningCost c = s.cost();
			c.addVariable(k.pose, aug.mean);
			c.addTerm(std::make_shared<CObjectPoseFeatureTerm>(k, Sxi));
			const auto r = c.gaussNewtonStep();
			Eigen::VectorXd xe = s.x;
			Eigen::MatrixXd Pe = s.P;
			append(xe, Pe, aug);
			const double e = std::max(relErr(c.stackedValues(), xe), relErr(r.covariance, Pe));
			std::cout << "[feature-space residual] n = " << n << ": mean "
			          << relErr(c.stackedValues(), xe) << ", covariance "
			          << relErr(r.covariance, Pe) << " (relative to Alg. 4)\n";
			if (n == 1)
				worstOneFeature = std::max(worstOneFeature, e);
			else
				smallestRigid = std::min(smallestRigid, e);
		}
	}
	EXPECT_LT(worstOneFeature, kTol);
	EXPECT_GT(smallestRigid, 1e-4);  // not a round-off difference: a different estimator
}

// Theorem A.3: static feature update (Alg. 5) = GN on prior + measurement residuals about mu.
TEST(StepEquivalence, StaticUpdateEquivalenceTheoremA3)
{
	for (auto model : {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (unsigned seed : {9u, 10u})
		{
			const TRandomState s = randomState(seed);
			const Eigen::Matrix2d R = Eigen::Matrix2d(Eigen::Vector2d(2e-3, 1e-3).asDiagonal());
			const Eigen::Vector3d ego = s.x.head<3>();
			std::vector<int> idx{0, 1, 2};
			std::vector<Eigen::Vector2d> z;
			Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, 7);
			Eigen::VectorXd nu(4);
			CRunningCost c = s.cost();
			for (int i = 0; i < 2; ++i)
			{
				const TVarKey k = TVarKey::landmark(10 + i);
				const Eigen::Vector2d f = s.x.segment<2>(s.idx.at(k));
				dynslam::models::Matrix23d Hx;
				Eigen::Matrix2d Hf;
				const Eigen::Vector2d zhat = dynslam::models::observe(model, ego, f, &Hx, &Hf);
				z.push_back(zhat + Eigen::Vector2d(0.05, -0.03));
				H.block<2, 3>(2 * i, 0) = Hx;
				H.block<2, 2>(2 * i, 3 + 2 * i) = Hf;
				nu.segment<2>(2 * i) = dynslam::models::innovation(model, z.back(), zhat);
				idx.push_back(s.idx.at(k));
				idx.push_back(s.idx.at(k) + 1);
				c.addTerm(std::make_shared<CMeasurementTerm>(5, k, z.back(), model, R));
			}
			const auto r = c.gaussNewtonStep();
			Eigen::VectorXd xe = s.x;
			RowMatrixXd Pe = s.P;
			Eigen::MatrixXd Rb = Eigen::MatrixXd::Zero(4, 4);
			Rb.topLeftCorner<2, 2>() = R;
			Rb.bottomRightCorner<2, 2>() = R;
			dynslam::ekf::sparseUpdate(xe, Pe, idx, H, nu, Rb);
			xe[2] = dynslam::models::wrapToPi(xe[2]);
			expectEqual("A.3 static update", c.stackedValues(), r.covariance, xe, Pe);
		}
}

// Theorems 4.2 / A.4: smoothing update (Alg. 6) = GN on prior + ||s(xi_{t-2}, xi_{t-1}, xi_t)||.
TEST(StepEquivalence, SmoothingUpdateEquivalenceTheorem42)
{
	for (int obj : {0, 2})
		for (unsigned seed : {11u, 12u})
		{
			const TRandomState s = randomState(seed);
			const int d = obj == 0 ? 3 : 2;
			const Eigen::MatrixXd Ss = Eigen::MatrixXd::Identity(d, d) * 1e-2;
			CRunningCost c = s.cost();
			c.addTerm(std::make_shared<CSmoothingTerm>(TVarKey::objectPose(obj, 3),
			                                           TVarKey::objectPose(obj, 4),
			                                           TVarKey::objectPose(obj, 5), Ss));
			const auto r = c.gaussNewtonStep();
			Eigen::VectorXd xe = s.x;
			RowMatrixXd Pe = s.P;
			dynslam::ekf::smoothingUpdate(xe, Pe, s.idx.at(TVarKey::objectPose(obj, 3)),
			                              s.idx.at(TVarKey::objectPose(obj, 4)),
			                              s.idx.at(TVarKey::objectPose(obj, 5)), Ss);
			xe[2] = dynslam::models::wrapToPi(xe[2]);
			expectEqual("4.2 smoothing update", c.stackedValues(), r.covariance, xe, Pe);
		}
}

// Theorem A.5: state propagation (Alg. 7) = add x_{t+1} with the odometry residual, then
// marginalize x_t, about (mu, g(mu)).
TEST(StepEquivalence, PropagationEquivalenceTheoremA5)
{
	for (unsigned seed : {13u, 14u, 15u})
	{
		const TRandomState s = randomState(seed);
		const Eigen::Vector3d u(1.2, 0.1, 0.07);
		const Eigen::Matrix3d Su = Eigen::Vector3d(1e-3, 2e-3, 1e-4).asDiagonal();
		CRunningCost c = s.cost();
		c.addVariable(TVarKey::ego(6), dynslam::models::composePose(s.x.head<3>(), u));
		c.addTerm(std::make_shared<COdometryTerm>(5, 6, u, Su));
		c.marginalize({TVarKey::ego(5)});
		// EKF order: the new ego pose first, then the rest in the original order.
		std::vector<TVarKey> order{TVarKey::ego(6)};
		for (size_t i = 1; i < s.keys.size(); ++i) order.push_back(s.keys[i]);
		Eigen::VectorXd xf(s.x.size());
		int off = 0;
		for (const auto& k : order)
		{
			xf.segment(off, c.dim(k)) = c.value(k);
			off += c.dim(k);
		}
		TGaussNewtonOptions o;
		const Eigen::MatrixXd Pf = c.covariance(order, o);
		Eigen::VectorXd xe = s.x;
		RowMatrixXd Pe = s.P;
		dynslam::ekf::propagate(xe, Pe, u, Su);
		expectEqual("A.5 propagation", xf, Pf, xe, Pe);
	}
}

// Badly scaled states (standard deviations from 1e-4 to 10, as on the highway with
// Sigma_0 = diag(1e-6, 1e-6, 1e-8) and far landmarks): the Jacobi-scaled solver keeps the
// agreement. (A random rotation of eigenvalues 1e-8..1e2 loses ~1e-6: kappa * eps.)
TEST(StepEquivalence, AugmentationAndUpdateEquivalenceBadlyScaled)
{
	TRandomState s = randomState(21, 0.05, 1);
	std::mt19937 rng(22);
	std::uniform_real_distribution<double> U(std::log(1e-4), std::log(10.0));
	Eigen::VectorXd d(s.x.size());
	for (int i = 0; i < d.size(); ++i) d[i] = std::exp(U(rng));
	s.P = d.asDiagonal() * s.P * d.asDiagonal();
	const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 1e-6;
	CRunningCost c = s.cost();
	const Eigen::Vector2d z(30, 4);
	c.addVariable(TVarKey::landmark(30), dynslam::models::cartesianInverse(s.x.head<3>(), z));
	c.addTerm(std::make_shared<CMeasurementTerm>(5, TVarKey::landmark(30), z,
	                                             MeasurementModel::Cartesian, R));
	const auto r = c.gaussNewtonStep();
	Eigen::VectorXd xe = s.x;
	Eigen::MatrixXd Pe = s.P;
	append(xe, Pe,
	       dynslam::ekf::featureAugmentation(MeasurementModel::Cartesian, s.x.head<3>(),
	                                         RowMatrixXd(s.P.topRows(3)), {z}, R));
	expectEqual("A.1 badly scaled", c.stackedValues(), r.covariance, xe, Pe);
}
