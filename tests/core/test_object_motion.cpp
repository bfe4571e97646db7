/** Object-centric motion models (models/object_motion.h, issue 13): the CV transition and the
 * sighting of an object feature z = h(x, g(xi, f0)_k) vs central differences, at seeded random
 * states and at the +-pi wrap of the ego heading and of the object's rotation; the process
 * noise against its closed form; ekf::predictSubset against the dense T P T^T + Q. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam::models;
using core_test::checkJacobian;
using core_test::VecFn;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
/** Object rotations: random, then at the wrap. */
std::vector<double> rotations()
{
	std::vector<double> a;
	for (int i = 0; i < 40; ++i) a.push_back(uniform(-M_PI, M_PI));
	for (double th : core_test::wrapHeadings()) a.push_back(th);
	return a;
}
}  // namespace

TEST(ObjectMotionJacobians, ConstantVelocityPrediction)
{
	dynslam_test::rng(1301);
	double worst = 0;
	for (const int d : {2, 3})
		for (const double th : rotations())
		{
			VectorXd s = core_test::randomVector(2 * d, -10, 10);
			if (d == 3)
			{
				s[2] = th;
				s[5] = uniform(-0.5, 0.5);  // turn rate: crosses the wrap from th near +-pi
			}
			const double dt = uniform(0.05, 1.0);
			MatrixXd J;
			const VectorXd out = cvPredict(s, dt, &J);
			if (d == 3)
			{
				EXPECT_LE(std::abs(out[2]), M_PI);
			}
			const VecFn f = [&](const VectorXd& v) { return cvPredict(v, dt); };
			EXPECT_TRUE(
			    checkJacobian(J, f, s, d == 3 ? std::vector<int>{2} : std::vector<int>{}, worst));
			// The mean: xi + dt v (angle compared modulo 2 pi), v unchanged.
			for (int i = 0; i < d; ++i)
				EXPECT_NEAR(wrapToPi(out[i] - s[i] - dt * s[d + i]), 0, 1e-12);
			EXPECT_EQ(out.tail(d), s.tail(d));
		}
	core_test::reportWorst("cvPredict", worst);
}

TEST(ObjectMotionJacobians, FeatureSighting)
{
	dynslam_test::rng(1302);
	double worst = 0;
	const auto rots = rotations();
	for (const auto model : {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (const int n : {1, 2, 4})
			for (size_t i = 0; i < rots.size(); ++i)
			{
				const Eigen::Matrix2Xd f0 = core_test::randomObject(n);
				const int d = n == 1 ? 2 : 3;
				VectorXd xi = core_test::randomVector(d, -5, 5);
				if (d == 3) xi[2] = rots[i];
				Eigen::Vector3d x = core_test::randomPose();
				x.head<2>() =
				    f0.rowwise().mean() + Eigen::Vector2d(uniform(-30, -20), uniform(5, 15));
				if (i >= rots.size() - 6) x[2] = rots[i];  // ego heading at the wrap too
				const int k = int(i) % n;
				Matrix23d J_z_x;
				MatrixXd J_z_xi, J_z_f0;
				observeObjectFeature(model, x, xi, f0, k, &J_z_x, &J_z_xi, &J_z_f0);
				const std::vector<int> ang = model == MeasurementModel::RangeBearing
				                                 ? std::vector<int>{1}
				                                 : std::vector<int>{};
				EXPECT_TRUE(checkJacobian(
				    J_z_x,
				    [&](const VectorXd& v)
				    { return VectorXd(observeObjectFeature(model, v, xi, f0, k)); },
				    x, ang, worst));
				EXPECT_TRUE(checkJacobian(
				    J_z_xi,
				    [&](const VectorXd& v)
				    { return VectorXd(observeObjectFeature(model, x, v, f0, k)); },
				    xi, ang, worst));
				EXPECT_TRUE(checkJacobian(
				    J_z_f0,
				    [&](const VectorXd& v) {
					    return VectorXd(observeObjectFeature(model, x, xi, core_test::unvec(v), k));
				    },
				    core_test::vec(f0), ang, worst));
			}
	core_test::reportWorst("observeObjectFeature", worst);
}

TEST(ObjectMotion, ProcessNoiseAndInitialVelocity)
{
	const MatrixXd Q = cvProcessNoise(Eigen::Vector3d(0.2, 0.3, 0.01), 0.5);
	ASSERT_EQ(Q.rows(), 6);
	EXPECT_DOUBLE_EQ(Q(0, 0), 0.2 * 0.125 / 3);
	EXPECT_DOUBLE_EQ(Q(0, 3), 0.2 * 0.25 / 2);
	EXPECT_DOUBLE_EQ(Q(3, 3), 0.2 * 0.5);
	EXPECT_DOUBLE_EQ(Q(2, 5), 0.01 * 0.25 / 2);
	EXPECT_EQ(Q(0, 1), 0.0);
	EXPECT_GE(core_test::minEigenvalue(Q), -1e-15);
	MatrixXd J;
	const VectorXd v = cvInitialVelocity(Eigen::Vector3d(1, 2, 0.3), 2.0, &J);
	EXPECT_TRUE(v.isApprox(Eigen::Vector3d(0.5, 1, 0.15)));
	EXPECT_TRUE(J.isApprox(MatrixXd::Identity(3, 3) / 2));
	EXPECT_THROW(cvInitialVelocity(Eigen::Vector3d::Zero(), 0.0), std::invalid_argument);
	EXPECT_THROW(cvProcessNoise(Eigen::Vector3d(-1, 0, 0), 0.5), std::invalid_argument);
	EXPECT_THROW(cvPredict(VectorXd::Zero(5), 0.5), std::invalid_argument);
}

TEST(EkfSteps, PredictSubsetMatchesDense)
{
	dynslam_test::rng(1303);
	const int n = 13;
	const MatrixXd P0 = core_test::randomSPD(n);
	const VectorXd x0 = core_test::randomVector(n, -5, 5);
	const std::vector<int> idx{4, 5, 6, 9, 10, 11};
	const MatrixXd F = core_test::randomSPD(6) + MatrixXd::Identity(6, 6);
	const MatrixXd Q = core_test::randomSPD(6, 0.1);
	const VectorXd xn = core_test::randomVector(6, -1, 1);
	MatrixXd T = MatrixXd::Identity(n, n);
	for (int r = 0; r < 6; ++r)
		for (int c = 0; c < 6; ++c) T(idx[r], idx[c]) = F(r, c);
	MatrixXd Pd = T * P0 * T.transpose();
	for (int r = 0; r < 6; ++r)
		for (int c = 0; c < 6; ++c) Pd(idx[r], idx[c]) += Q(r, c);
	VectorXd x = x0;
	dynslam::ekf::RowMatrixXd P = P0;
	dynslam::ekf::predictSubset(x, P, idx, xn, F, Q);
	EXPECT_LT((MatrixXd(P) - Pd).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_EQ(MatrixXd(P), MatrixXd(P).transpose());
	for (int i = 0; i < n; ++i)
	{
		const auto it = std::find(idx.begin(), idx.end(), i);
		EXPECT_EQ(x[i], it == idx.end() ? x0[i] : xn[it - idx.begin()]);
	}
	EXPECT_THROW(dynslam::ekf::predictSubset(x, P, {0, 99}, xn.head(2), F.topLeftCorner(2, 2),
	                                         Q.topLeftCorner(2, 2)),
	             std::out_of_range);
}
