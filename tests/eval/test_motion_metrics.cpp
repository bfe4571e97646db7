/** Relative pose error and the object motion error in VDO-SLAM's form (motion_metrics.h). */
#include <dynslam/core/models/se2.h>
#include <dynslam/eval/motion_metrics.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace dynslam;
using namespace dynslam::eval;

namespace
{
/** G(xi) applied to a point, written out from the definition (not via SE(2) composition). */
Eigen::Vector2d applyG(const Eigen::Vector3d& xi, const Eigen::Vector2d& c0,
                       const Eigen::Vector2d& p)
{
	return models::rot2(xi.z()) * (p - c0) + c0 + xi.head<2>();
}
Eigen::Vector2d applyPose(const Eigen::Vector3d& T, const Eigen::Vector2d& p)
{
	return models::rot2(T.z()) * p + T.head<2>();
}

/** A 4-corner object turning while it drives, seen at every step; ego on a curve. */
io::TGroundTruth makeTruth(size_t n)
{
	io::TGroundTruth gt;
	io::TObjectGroundTruth o;
	o.object = 0;
	o.num_features = 4;
	o.first_step = 0;
	Eigen::Matrix<double, 2, 4> box;
	box << 2, 2, -2, -2, 1, -1, -1, 1;
	const Eigen::Vector2d c0(10, 3);
	for (size_t k = 0; k < n; ++k)
	{
		gt.t.push_back(0.1 * double(k));
		gt.ego.emplace_back(1.0 * double(k), 0.02 * double(k * k), 0.04 * double(k));
		const Eigen::Vector3d xi(1.2 * double(k), 0.1 * double(k * k) / 4, 0.05 * double(k));
		o.pose.push_back(xi);
		Eigen::Matrix2Xd f(2, 4);
		for (int j = 0; j < 4; ++j) f.col(j) = applyG(xi, c0, c0 + box.col(j));
		o.features.push_back(f);
		o.visible.push_back(1);
	}
	gt.objects.push_back(o);
	return gt;
}

TRunEstimates perfectEstimates(const io::TGroundTruth& gt)
{
	TRunEstimates est;
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		est.ego.push_back({int(k), gt.ego[k], Eigen::Matrix3d::Identity() * 1e-4});
		est.object_poses.push_back(
		    {0, int(k), gt.objects[0].pose[k], Eigen::Matrix3d::Identity(), {}, {}, {}});
	}
	for (int j = 0; j < 4; ++j)
		est.object_features.push_back(
		    {0, j, gt.objects[0].features[0].col(j), Eigen::Matrix2d::Identity()});
	return est;
}
}  // namespace

TEST(MotionMetrics, BodyFrameMotionIsTheWorldMotionSeenFromTheObject)
{
	// For a world point q: G(xi_k) G(xi_{k-1})^-1 q (from the definition of G) equals
	// L_{k-1} M L_{k-1}^-1 q with L_{k-1} = (c0 + d_{k-1}, dtheta_{k-1}) and M the body-frame
	// motion; random poses, centres and points.
	std::mt19937 rng(3);
	std::uniform_real_distribution<double> U(-5, 5);
	for (int trial = 0; trial < 20; ++trial)
	{
		const Eigen::Vector3d a(U(rng), U(rng), U(rng) / 2), b(U(rng), U(rng), U(rng) / 2);
		const Eigen::Vector2d c0(U(rng), U(rng)), q(U(rng), U(rng));
		const Eigen::Vector2d p0 = models::rot2(-a.z()) * (q - c0 - a.head<2>()) + c0;  // G(a)^-1 q
		const Eigen::Vector2d expected = applyG(b, c0, p0);
		const Eigen::Vector3d L(c0.x() + a.x(), c0.y() + a.y(), a.z());
		const Eigen::Vector2d inBody = models::rot2(-L.z()) * (q - L.head<2>());
		const Eigen::Vector3d M = bodyFrameMotion(a, b, c0);
		EXPECT_LT((applyPose(L, applyPose(M, inBody)) - expected).norm(), 1e-12);
	}
	// independent of the world origin: shifting c0 and the truth together changes nothing
	const Eigen::Vector3d a(0.3, -0.2, 0.1), b(1.1, 0.4, 0.25);
	EXPECT_LT((bodyFrameMotion(a, b, Eigen::Vector2d(1, 2)) -
	           bodyFrameMotion(a, b, Eigen::Vector2d(300, -500)))
	              .norm(),
	          1e-12);
}

TEST(MotionMetrics, PerfectEstimatesHaveZeroErrors)
{
	const io::TGroundTruth gt = makeTruth(30);
	const TRunEstimates est = perfectEstimates(gt);
	const TObjectErrors e = objectErrors(gt, est);
	EXPECT_EQ(e.motion.n, 29u);
	EXPECT_EQ(e.motion.n_rot, 29u);
	EXPECT_LT(e.motion.trans_rmse, 1e-12);
	EXPECT_LT(e.motion.rot_rmse, 1e-12);
	EXPECT_EQ(e.position_n, 30u);
	EXPECT_LT(e.position_rmse, 1e-12);
	const TRelativePoseError r = relativePoseError(gt, est.ego, 10);
	EXPECT_EQ(r.n, 20u);
	EXPECT_LT(r.trans_rmse, 1e-12);
	EXPECT_LT(r.rot_rmse, 1e-12);
}

TEST(MotionMetrics, OneDisplacedPoseCostsTwoMotions)
{
	// xi_5 off by (0.3, -0.4) with the rotation right: the motions 4->5 and 5->6 are wrong.
	// 4->5 and 5->6: the body-frame translation is off by the 0.5 m displacement, rotated.
	const io::TGroundTruth gt = makeTruth(12);
	TRunEstimates est = perfectEstimates(gt);
	est.object_poses[5].mean.head<2>() += Eigen::Vector2d(0.3, -0.4);
	const TObjectErrors e = objectErrors(gt, est);
	EXPECT_EQ(e.motion.n, 11u);
	EXPECT_NEAR(e.motion.trans_mean, 2 * 0.5 / 11, 1e-12);
	EXPECT_NEAR(e.motion.trans_rmse, std::sqrt(2 * 0.25 / 11), 1e-12);
	EXPECT_LT(e.motion.rot_rmse, 1e-12);
	EXPECT_NEAR(e.position_rmse, std::sqrt(0.25 / 12), 1e-12);
	// a rotation error of 0.1 rad at step 5: rotation errors 0.1 at 4->5 and 5->6
	est = perfectEstimates(gt);
	est.object_poses[5].mean.z() += 0.1;
	const TObjectErrors r = objectErrors(gt, est);
	EXPECT_NEAR(r.motion.rot_mean, 2 * 0.1 / 11, 1e-12);
	EXPECT_NEAR(r.position_rmse, 0, 1e-12);  // the rotation centre does not move
}

TEST(MotionMetrics, TranslationOnlyObjectsAndGaps)
{
	io::TGroundTruth gt = makeTruth(10);
	TRunEstimates est = perfectEstimates(gt);
	for (auto& p : est.object_poses)
	{
		p.mean = Eigen::Vector2d(p.mean.head<2>());
		p.cov = Eigen::Matrix2d::Identity();
	}
	// the truth rotates, a 2-dof estimate cannot: compared as pure translations d_k - d_{k-1}
	est.object_poses.erase(est.object_poses.begin() + 4);  // step 4 unseen: 3->4, 4->5 not scored
	const TObjectErrors e = objectErrors(gt, est);
	EXPECT_EQ(e.motion.n, 7u);
	EXPECT_EQ(e.motion.n_rot, 0u);
	EXPECT_LT(e.motion.trans_rmse, 1e-12);
	EXPECT_TRUE(std::isnan(e.motion.rot_rmse));
}

TEST(MotionMetrics, RelativePoseErrorSeesAJumpOnce)
{
	// a 1 m jump between steps 4 and 5 (ego heading 0): with delta 1 only the pair (4, 5)
	// is wrong; a constant world offset of the whole path costs nothing
	io::TGroundTruth gt;
	TRunEstimates est;
	for (int k = 0; k < 11; ++k)
	{
		gt.t.push_back(k);
		gt.ego.emplace_back(k, 0, 0);
		est.ego.push_back(
		    {k, Eigen::Vector3d(k + (k >= 5 ? 1.0 : 0.0), 0, 0), Eigen::Matrix3d::Identity()});
	}
	const TRelativePoseError r = relativePoseError(gt, est.ego, 1);
	EXPECT_EQ(r.n, 10u);
	EXPECT_NEAR(r.trans_rmse, std::sqrt(1.0 / 10), 1e-12);
	for (auto& e : est.ego)
		e.mean = models::composePose(Eigen::Vector3d(3, -2, 0.7), gt.ego[size_t(e.step)]);
	const TRelativePoseError c = relativePoseError(gt, est.ego, 3);
	EXPECT_EQ(c.n, 8u);
	EXPECT_LT(c.trans_rmse, 1e-12);
	EXPECT_LT(c.rot_rmse, 1e-12);
}
