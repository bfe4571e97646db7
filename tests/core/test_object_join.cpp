/** Late joining (doc/results/classification.md, "Grouping"): the object pose with its centroid
 * fixed by the founders (models::objectPoseInverse / objectPoseMap, centroidCols) and the time-0
 * position of a feature that joins an object later (ekf::appendJoinedFeatures): values on
 * noise-free data, Jacobians against central differences, the noise layout. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/object_pose.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam;

namespace
{
/** Three founders and one joiner at time 0, moved by xi. */
struct TObject
{
	Eigen::Matrix2Xd f0{2, 4};
	Eigen::Vector3d xi{1.7, -0.6, 0.4};
	TObject() { f0 << 10, 12, 11, 13.5, 3, 3.5, 5, 4.2; }
	Eigen::Matrix2Xd ft() const { return models::objectPoseMap(xi, f0, nullptr, nullptr, 3); }
};

/** x = [f0 of the founders (3), ft of founders 0 and 2, ft of the joiner]. */
Eigen::VectorXd stateOf(const TObject& o)
{
	const Eigen::Matrix2Xd ft = o.ft();
	Eigen::VectorXd x(12);
	x << o.f0.col(0), o.f0.col(1), o.f0.col(2), ft.col(0), ft.col(2), ft.col(3);
	return x;
}

ekf::ObjectPoseLinearization joined(const Eigen::VectorXd& x, int nc)
{
	const Eigen::Matrix2d Sigma = Eigen::Vector2d(0.01, 0.02).asDiagonal();
	if (nc == 1)  // one founder (feature 0): translation-only pose
		return ekf::appendJoinedFeatures(x, ekf::linearizeObjectPose(x, {0}, {6}, {0}, Sigma), 1,
		                                 {10}, 2);
	return ekf::appendJoinedFeatures(
	    x, ekf::linearizeObjectPose(x, {0, 2, 4}, {6, 8}, {0, 2}, Sigma, 3), 3, {10}, 4);
}
}  // namespace

TEST(ObjectJoin, FoundersFixTheCentroid)
{
	const TObject o;
	const Eigen::Matrix2Xd ft = o.ft();
	// The joiner seen with the founders: the pose keeps its meaning (centroid of the founders).
	EXPECT_LT((models::objectPoseInverse(o.f0, ft, {}, nullptr, nullptr, 3) - o.xi).norm(), 1e-12);
	// With the centroid over all four columns the same points give another translation.
	EXPECT_GT((models::objectPoseInverse(o.f0, ft).head<2>() - o.xi.head<2>()).norm(), 0.1);
	EXPECT_THROW(models::objectPoseInverse(o.f0, ft, {}, nullptr, nullptr, 5),
	             std::invalid_argument);
	// Jacobians with the founders' centroid.
	Eigen::VectorXd v(16);
	v << Eigen::Map<const Eigen::VectorXd>(o.f0.data(), 8),
	    Eigen::Map<const Eigen::VectorXd>(ft.data(), 8);
	const core_test::VecFn g = [](const Eigen::VectorXd& w)
	{
		const Eigen::Matrix2Xd a = Eigen::Map<const Eigen::Matrix2Xd>(w.data(), 2, 4);
		const Eigen::Matrix2Xd b = Eigen::Map<const Eigen::Matrix2Xd>(w.data() + 8, 2, 4);
		return Eigen::VectorXd(models::objectPoseInverse(a, b, {}, nullptr, nullptr, 3));
	};
	Eigen::MatrixXd G1, G2;
	models::objectPoseInverse(o.f0, ft, {}, &G1, &G2, 3);
	Eigen::MatrixXd G(3, 16);
	G << G1, G2;
	double worst = 0;
	EXPECT_TRUE(core_test::checkJacobian(G, g, v, {2}, worst));
	Eigen::MatrixXd J_ft_f0;
	models::objectPoseMap(o.xi, o.f0, nullptr, &J_ft_f0, 3);
	const core_test::VecFn m = [&](const Eigen::VectorXd& w)
	{
		const Eigen::Matrix2Xd a = Eigen::Map<const Eigen::Matrix2Xd>(w.data(), 2, 4);
		const Eigen::Matrix2Xd b = models::objectPoseMap(o.xi, a, nullptr, nullptr, 3);
		return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(b.data(), 8));
	};
	EXPECT_TRUE(core_test::checkJacobian(J_ft_f0, m, v.head(8), {}, worst));
	core_test::reportWorst("founders' centroid Jacobians", worst);
}

TEST(ObjectJoin, JoinerTimeZeroPositionAndJacobian)
{
	const TObject o;
	const Eigen::VectorXd x = stateOf(o);
	double worst = 0;
	for (const int nc : {3, 1})
	{
		const ekf::ObjectPoseLinearization j = joined(x, nc);
		const int d = nc == 1 ? 2 : 3, pad = nc == 1 ? 2 : 4;
		ASSERT_EQ(j.xi.size(), pad + 2);
		ASSERT_EQ(j.idx.size(), size_t(2 * nc + (nc == 1 ? 2 : 4) + 2));
		// The joiner's f0, moved by the pose, is where it is seen now; 3-dof: its true f0.
		Eigen::Matrix2Xd f0(2, nc + 1);
		for (int k = 0; k < nc; ++k) f0.col(k) = x.segment<2>(2 * k);
		f0.col(nc) = j.xi.segment<2>(pad);
		if (nc == 3)
		{
			EXPECT_LT((j.xi.segment<2>(pad) - o.f0.col(3)).norm(), 1e-12);
			EXPECT_LT((models::objectPoseMap(j.xi.head<3>(), f0, nullptr, nullptr, 3).col(3) -
			           x.segment<2>(10))
			              .norm(),
			          1e-12);
		}
		else
			EXPECT_LT((j.xi.segment<2>(pad) + j.xi.head<2>() - x.segment<2>(10)).norm(), 1e-12);
		// Gamma over idx against central differences of the whole construction.
		const std::vector<int> idx = j.idx;
		const core_test::VecFn f = [&](const Eigen::VectorXd& w)
		{
			Eigen::VectorXd full = x;
			for (size_t i = 0; i < idx.size(); ++i) full[idx[i]] = w[Eigen::Index(i)];
			return Eigen::VectorXd(joined(full, nc).xi);
		};
		Eigen::VectorXd w(idx.size());
		for (size_t i = 0; i < idx.size(); ++i) w[Eigen::Index(i)] = x[idx[i]];
		EXPECT_TRUE(core_test::checkJacobian(
		    j.Gamma, f, w, d == 3 ? std::vector<int>{2} : std::vector<int>{}, worst))
		    << "nc = " << nc;
		// Noise: the pose's, mapped to the joiner (shared), pads independent with variance 1.
		EXPECT_LT((j.noise - j.noise.transpose()).norm(), 1e-15);
		EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(j.noise).eigenvalues().minCoeff(),
		          -1e-12);
		for (int i = d; i < pad; ++i) EXPECT_EQ(j.noise(i, i), 1.0);
		EXPECT_GT(j.noise.block(pad, 0, 2, d).norm(), 0) << "the joiner shares the pose noise";
	}
	core_test::reportWorst("joiner f0 Jacobian", worst);
	const ekf::ObjectPoseLinearization pose = ekf::linearizeObjectPose(
	    x, {0, 2, 4}, {6, 8}, {0, 2}, Eigen::Matrix2d::Identity() * 0.01, 3);
	EXPECT_THROW(ekf::appendJoinedFeatures(x, pose, 3, {10}, 2), std::invalid_argument);
	EXPECT_THROW(ekf::appendJoinedFeatures(x, pose, 3, {11}, 4), std::out_of_range);
}
