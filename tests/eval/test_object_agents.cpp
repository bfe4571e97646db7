/** eval::scoreClassifyingAgents: the agent_* feature and pose cells of classifying rows
 * (doc/metrics.md "Objects of classifying rows"): each true object against the estimated object
 * with most of its readings, from that object's own time 0. */
#include <dynslam/eval/object_matching.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynslam;
using namespace dynslam::eval;

namespace
{
constexpr int kSteps = 6;

Eigen::Vector2d rot(double a, const Eigen::Vector2d& p)
{
	return {std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y()};
}

/** True object 0: two features (10, 0) and (12, 0) at step 0, turning 0.1 rad and moving (1, 0)
 * per step about their centroid (11, 0). True object 1: one feature at (0, 5 + k - 1), first
 * seen at step 1. */
io::TGroundTruth truth()
{
	io::TGroundTruth gt;
	io::TObjectGroundTruth a, b;
	a.object = 0;
	a.num_features = 2;
	a.first_step = 0;
	b.object = 1;
	b.num_features = 1;
	b.first_step = 1;
	const double nan = std::nan("");
	for (int k = 0; k < kSteps; ++k)
	{
		gt.t.push_back(0.5 * k);
		gt.ego.emplace_back(0, 0, 0);
		Eigen::Matrix2Xd fa(2, 2), fb(2, 1);
		for (int i = 0; i < 2; ++i)
			fa.col(i) = rot(0.1 * k, Eigen::Vector2d(-1 + 2 * i, 0)) + Eigen::Vector2d(11 + k, 0);
		fb.col(0) = Eigen::Vector2d(0, 5 + k - 1);
		a.features.push_back(fa);
		a.pose.emplace_back(k, 0, 0.1 * k);
		a.visible.push_back(1);
		b.features.push_back(fb);
		b.pose.push_back(k < 1 ? Eigen::Vector3d(nan, nan, nan) : Eigen::Vector3d(0, k - 1, 0));
		b.visible.push_back(k >= 1);
	}
	gt.objects = {a, b};
	return gt;
}

io::TReadingClass moving(int step, int32_t object, int32_t feature)
{
	io::TReadingClass r;
	r.step = step;
	r.cls = io::TrueClass::Moving;
	r.object = object;
	r.feature = feature;
	return r;
}

TObjectPoseEstimate pose(int32_t obj, int step, const Eigen::Vector3d& mean)
{
	TObjectPoseEstimate p;
	p.object = obj;
	p.step = step;
	p.mean = mean;
	p.cov = Eigen::Matrix3d::Identity();
	return p;
}

/** One reading per listed (step, estimated object, estimated feature, true object, true
 * feature). */
struct TReads
{
	TReadingObjects est;
	std::vector<io::TReadingClass> truth;
	void add(int step, int32_t o, int32_t f, int32_t to, int32_t tf)
	{
		est.object.push_back(o);
		est.feature.push_back(f);
		truth.push_back(moving(step, to, tf));
	}
};
}  // namespace

TEST(ObjectAgents, FoundedAtTheFirstSightingEqualsTheLabelledScoring)
{
	// The router's object 5 is true object 0, founded at its first sighting with both features:
	// its cells equal computeRunMetrics on the same estimates numbered as the truth.
	const io::TGroundTruth gt = truth();
	TRunEstimates labelled;
	labelled.object_features = {{0, 0, {10.02, -0.01}, Eigen::Matrix2d::Identity()},
	                            {0, 1, {11.97, 0.03}, Eigen::Matrix2d::Identity()}};
	for (int k = 1; k < kSteps; ++k)
		labelled.object_poses.push_back(pose(0, k, {k + 0.01 * k, -0.02, 0.1 * k + 0.003}));
	const TRunMetrics ref = computeRunMetrics(gt, labelled);
	TRunEstimates classifying = labelled;
	for (auto& f : classifying.object_features) f.object = 5;
	for (auto& p : classifying.object_poses) p.object = 5;
	TReads r;
	for (int k = 0; k < kSteps; ++k)
		for (int i = 0; i < 2; ++i) r.add(k, 5, i, 0, i);
	TRunMetrics m = computeRunMetrics(gt, classifying);
	EXPECT_TRUE(std::isnan(m.objects[0].poses.x));  // by number: no object 0
	const auto agents = scoreClassifyingAgents(m, gt, classifying, r.est, r.truth);
	ASSERT_EQ(agents.size(), 2u);
	EXPECT_EQ(agents[0].estimated, 5);
	EXPECT_EQ(agents[0].first_step, 0);
	const TObjectMetrics &a = m.objects[0], &b = ref.objects[0];
	EXPECT_NEAR(a.features.x, b.features.x, 1e-12);
	EXPECT_NEAR(a.features.y, b.features.y, 1e-12);
	EXPECT_NEAR(a.poses.x, b.poses.x, 1e-12);
	EXPECT_NEAR(a.poses.y, b.poses.y, 1e-12);
	EXPECT_NEAR(a.poses.theta, b.poses.theta, 1e-12);
	EXPECT_EQ(a.poses.n_xy, 5u);
	EXPECT_EQ(a.features_missing, 0u);
	EXPECT_GT(b.poses.x, 0.01);  // not a trivially zero comparison
}

TEST(ObjectAgents, LateFoundedObjectIsScoredFromItsOwnTimeZero)
{
	// Estimated object 7 is founded at step 2 by true feature 1 alone (its feature 0); true
	// feature 0 joins at step 3 (its feature 1). Its poses are relative to step 2 about its
	// founder: the truth is the motion of true feature 1 since step 2 (by hand, the feature
	// track of a rigid body): d'_k = (k - 2 + cos 0.1k - cos 0.2, sin 0.1k - sin 0.2),
	// theta'_k = 0.1 (k - 2). Object 8 (also true object 0, fewer readings) is not scored.
	const io::TGroundTruth gt = truth();
	TReads r;
	for (int k = 0; k < 2; ++k) r.add(k, -1, -1, 0, 1);  // undecided
	for (int k = 2; k < kSteps; ++k) r.add(k, 7, 0, 0, 1);
	for (int k = 3; k < kSteps; ++k) r.add(k, 7, 1, 0, 0);
	for (int k = 4; k < kSteps; ++k) r.add(k, 8, 0, 0, 0);
	TRunEstimates est;
	const Eigen::Vector2d f1 = gt.objects[0].features[2].col(1),
	                      f0 = gt.objects[0].features[2].col(0);
	est.object_features = {{7, 0, f1 + Eigen::Vector2d(0.03, 0.04), Eigen::Matrix2d::Identity()},
	                       {7, 1, f0 + Eigen::Vector2d(-0.03, 0.04), Eigen::Matrix2d::Identity()},
	                       {8, 0, f0 + Eigen::Vector2d(5, 5), Eigen::Matrix2d::Identity()}};
	for (int k = 3; k < kSteps; ++k)
	{
		const double dx = k - 2 + std::cos(0.1 * k) - std::cos(0.2);
		const double dy = std::sin(0.1 * k) - std::sin(0.2);
		est.object_poses.push_back(pose(7, k, {dx + 0.1, dy - 0.2, 0.1 * (k - 2) + 0.01}));
		est.object_poses.push_back(pose(8, k, {dx + 3, dy + 3, 1}));
	}
	TRunMetrics m = computeRunMetrics(gt, est);
	const auto agents = scoreClassifyingAgents(m, gt, est, r.est, r.truth);
	ASSERT_EQ(agents.size(), 2u);
	EXPECT_EQ(agents[0].estimated, 7);
	EXPECT_EQ(agents[0].candidates, 2u);
	EXPECT_EQ(agents[0].readings, 7u);
	EXPECT_EQ(agents[0].first_step, 2);
	EXPECT_EQ(agents[0].features_matched, 2u);
	const TObjectMetrics& a = m.objects[0];
	EXPECT_NEAR(a.poses.x, 0.1, 1e-12);
	EXPECT_NEAR(a.poses.y, 0.2, 1e-12);
	EXPECT_NEAR(a.poses.theta, 0.01, 1e-12);
	EXPECT_EQ(a.poses.n_xy, 3u);
	EXPECT_NEAR(a.features.x, 0.03, 1e-12);
	EXPECT_NEAR(a.features.y, 0.04, 1e-12);
	EXPECT_EQ(a.features_missing, 0u);
	// True object 1 has no estimated object: empty cells, said in the match.
	EXPECT_EQ(agents[1].estimated, -1);
	EXPECT_EQ(agents[1].candidates, 0u);
	EXPECT_EQ(m.objects[1].object, 1);
	EXPECT_TRUE(std::isnan(m.objects[1].poses.x));
	EXPECT_TRUE(std::isnan(m.objects[1].features.x));
	// Readings and class truth of different lengths are refused.
	TReadingObjects shorter = r.est;
	shorter.feature.pop_back();
	EXPECT_THROW(scoreClassifyingAgents(m, gt, est, shorter, r.truth), std::invalid_argument);
}

TEST(ObjectAgents, TiesGoToTheSmallerEstimatedObject)
{
	// Two estimated objects with two readings each of true object 1 (one feature, first seen
	// at step 1): the smaller number (3) is scored; its pose at step 3 is 0.5 m off in x.
	const io::TGroundTruth gt = truth();
	TReads r;
	r.add(1, 4, 0, 1, 0);
	r.add(2, 4, 0, 1, 0);
	r.add(1, 3, 0, 1, 0);
	r.add(2, 3, 0, 1, 0);
	TRunEstimates est;
	est.object_features = {{3, 0, {0, 5}, Eigen::Matrix2d::Identity()},
	                       {4, 0, {0, 5}, Eigen::Matrix2d::Identity()}};
	TObjectPoseEstimate p3 = pose(3, 3, {0.5, 2, 0}), p4 = pose(4, 3, {2, 2, 0});
	for (auto* p : {&p3, &p4})
	{
		p->mean = p->mean.head<2>().eval();
		p->cov = Eigen::Matrix2d::Identity();
	}
	est.object_poses = {p4, p3};
	TRunMetrics m = computeRunMetrics(gt, est);
	const auto agents = scoreClassifyingAgents(m, gt, est, r.est, r.truth);
	EXPECT_EQ(agents[1].estimated, 3);
	EXPECT_EQ(agents[1].candidates, 2u);
	EXPECT_EQ(agents[1].first_step, 1);
	EXPECT_NEAR(m.objects[1].poses.x, 0.5, 1e-12);
	EXPECT_NEAR(m.objects[1].poses.y, 0.0, 1e-12);
	EXPECT_TRUE(std::isnan(m.objects[1].poses.theta));
	EXPECT_TRUE(m.objects[1].translation_only);
}
