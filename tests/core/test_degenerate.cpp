/** Degenerate and invalid input of the core models, and the landmark ID ranges. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/smoothing.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam::models;
using dynslam_test::uniform;
using Eigen::VectorXd;

TEST(ObjectPoseDegenerate, OneSeenFeature)
{
	dynslam_test::rng(301);
	const Eigen::Matrix2Xd f0 = core_test::randomObject(3);
	const Eigen::Matrix2Xd ft = objectPoseMap(Eigen::Vector3d(1, 2, 0.3), f0);
	EXPECT_THROW(objectPoseInverse(f0, ft.col(1), {1}), std::domain_error);
	EXPECT_THROW(objectPoseInverse(f0.col(0), ft.col(0)), std::domain_error);
	Eigen::MatrixXd G1, G2;
	EXPECT_THROW(objectPoseInverse(f0.col(0), ft.col(0), {}, &G1, &G2), std::domain_error);
}

TEST(ObjectPoseDegenerate, AllIdenticalFeatures)
{
	dynslam_test::rng(302);
	for (int trial = 0; trial < 100; ++trial)
	{
		const int n = 2 + trial % 5;
		// random coordinates: the centroid of identical values is not always exactly that value
		const Eigen::Vector2d p = core_test::randomVector(2, -100, 100);
		const Eigen::Matrix2Xd same = p.replicate(1, n);
		const Eigen::Matrix2Xd distinct = core_test::randomObject(n);
		EXPECT_THROW(objectPoseInverse(same, distinct), std::domain_error)
		    << "identical at time 0, p = " << p.transpose() << ", n = " << n;
		EXPECT_THROW(objectPoseInverse(distinct, same), std::domain_error)
		    << "identical at time t, p = " << p.transpose() << ", n = " << n;
		EXPECT_THROW(objectPoseInverse(same, same), std::domain_error);
		// identical at both times, at different places (rounding noise must not fix a rotation)
		const Eigen::Matrix2Xd same2 = core_test::randomVector(2, -100, 100).replicate(1, n);
		EXPECT_THROW(objectPoseInverse(same, same2), std::domain_error)
		    << "identical at both times, n = " << n;
	}
	// a subset whose seen features coincide at time 0, although the object's do not
	Eigen::Matrix2Xd f0(2, 3), ft(2, 2);
	f0 << 1, 1, 4, 2, 2, 0;
	ft << 5, 6, 1, 2;
	EXPECT_THROW(objectPoseInverse(f0, ft, {0, 1}), std::domain_error);
	EXPECT_NO_THROW(objectPoseInverse(f0, ft, {0, 2}));
}

TEST(ObjectPoseDegenerate, InvalidArguments)
{
	dynslam_test::rng(303);
	const Eigen::Matrix2Xd f0 = core_test::randomObject(4);
	const Eigen::Matrix2Xd ft = objectPoseMap(Eigen::Vector3d(1, 2, 0.3), f0);
	// m != n without a correspondence list
	EXPECT_THROW(objectPoseInverse(f0, ft.leftCols(3)), std::invalid_argument);
	EXPECT_THROW(objectPoseInverse(f0.leftCols(3), ft), std::invalid_argument);
	// list size != m
	EXPECT_THROW(objectPoseInverse(f0, ft.leftCols(3), {0, 1}), std::invalid_argument);
	EXPECT_THROW(objectPoseInverse(f0, ft.leftCols(2), {0, 1, 2}), std::invalid_argument);
	// bad or duplicate indices
	EXPECT_THROW(objectPoseInverse(f0, ft.leftCols(2), {0, 4}), std::invalid_argument);
	EXPECT_THROW(objectPoseInverse(f0, ft.leftCols(2), {-1, 1}), std::invalid_argument);
	EXPECT_THROW(objectPoseInverse(f0, ft.leftCols(2), {1, 1}), std::invalid_argument);
	EXPECT_THROW(objectPoseInverse(f0, ft, {0, 1, 2, 2}), std::invalid_argument);
	// a valid permuted list works
	Eigen::Matrix2Xd ftp(2, 4);
	ftp << ft.col(2), ft.col(0), ft.col(3), ft.col(1);
	const Eigen::Vector3d xi = objectPoseInverse(f0, ftp, {2, 0, 3, 1});
	EXPECT_LT((xi - Eigen::Vector3d(1, 2, 0.3)).norm(), 1e-9);
	// objectPoseMap needs at least one feature
	EXPECT_THROW(objectPoseMap(Eigen::Vector3d(0, 0, 0), Eigen::Matrix2Xd(2, 0)),
	             std::invalid_argument);
}

TEST(MeasurementDegenerate, FeatureAtTheSensor)
{
	const Eigen::Vector3d x(3, -2, 0.7);
	Matrix23d J_z_x;
	Eigen::Matrix2d J_z_f;
	EXPECT_THROW(rangeBearingObserve(x, x.head<2>()), std::domain_error);
	EXPECT_THROW(rangeBearingObserve(x, x.head<2>(), &J_z_x, &J_z_f), std::domain_error);
	EXPECT_THROW(observe(MeasurementModel::RangeBearing, x, x.head<2>()), std::domain_error);
	EXPECT_THROW(cartesianToRangeBearing(Eigen::Vector2d::Zero()), std::domain_error);
	// Cartesian is defined there: z = 0
	EXPECT_EQ(cartesianObserve(x, x.head<2>()), Eigen::Vector2d::Zero());
}

TEST(SmoothingDegenerate, BadDimensions)
{
	EXPECT_THROW(smoothingResidual(VectorXd::Zero(4), VectorXd::Zero(4), VectorXd::Zero(4)),
	             std::invalid_argument);
	EXPECT_THROW(smoothingResidual(VectorXd::Zero(1), VectorXd::Zero(1), VectorXd::Zero(1)),
	             std::invalid_argument);
	EXPECT_THROW(smoothingResidual(VectorXd::Zero(3), VectorXd::Zero(2), VectorXd::Zero(3)),
	             std::invalid_argument);
	EXPECT_THROW(smoothingResidual(VectorXd::Zero(2), VectorXd::Zero(2), VectorXd::Zero(3)),
	             std::invalid_argument);
}

namespace ids = dynslam::ids;

TEST(LandmarkIds, Classify)
{
	static_assert(ids::classify(0) == ids::IdKind::Static);
	EXPECT_EQ(ids::classify(0), ids::IdKind::Static);
	EXPECT_EQ(ids::classify(12), ids::IdKind::Static);
	EXPECT_EQ(ids::classify(99'999), ids::IdKind::Static);
	EXPECT_EQ(ids::classify(100'000), ids::IdKind::ObjectFeature);
	EXPECT_EQ(ids::classify(101'003), ids::IdKind::ObjectFeature);
	EXPECT_EQ(ids::classify(-1), ids::IdKind::Invalid);
	EXPECT_EQ(ids::classify(INT32_MIN), ids::IdKind::Invalid);
	EXPECT_TRUE(ids::isStatic(5));
	EXPECT_FALSE(ids::isStatic(100'000));
	EXPECT_TRUE(ids::isObjectFeature(100'000));
	EXPECT_FALSE(ids::isObjectFeature(99'999));
	EXPECT_FALSE(ids::isObjectFeature(-5));
}

TEST(LandmarkIds, ObjectFeatureIdRoundTrip)
{
	EXPECT_EQ(ids::objectFeatureId(0, 0), 100'000);
	EXPECT_EQ(ids::objectFeatureId(1, 3), 101'003);
	EXPECT_EQ(ids::objectFeatureId(2, 999), 102'999);
	dynslam_test::rng(304);
	std::vector<std::pair<int32_t, int32_t>> cases = {
	    {0, 0}, {0, 999}, {ids::kMaxObject, 0}, {ids::kMaxObject, 999}};
	for (int i = 0; i < 200; ++i)
		cases.emplace_back(int32_t(dynslam_test::rng()() % uint32_t(ids::kMaxObject + 1)),
		                   int32_t(dynslam_test::rng()() % uint32_t(ids::kFeaturesPerObject)));
	for (const auto& [obj, k] : cases)
	{
		const int32_t id = ids::objectFeatureId(obj, k);
		EXPECT_EQ(ids::classify(id), ids::IdKind::ObjectFeature) << id;
		EXPECT_EQ(ids::objectOf(id), obj);
		EXPECT_EQ(ids::featureOf(id), k);
	}
	// the largest valid object's features fit in int32
	EXPECT_GT(ids::objectFeatureId(ids::kMaxObject, 999), ids::objectFeatureId(ids::kMaxObject, 0));
}

TEST(LandmarkIds, OutOfRangeThrows)
{
	EXPECT_THROW(ids::objectFeatureId(-1, 0), std::out_of_range);
	EXPECT_THROW(ids::objectFeatureId(ids::kMaxObject + 1, 0), std::out_of_range);
	EXPECT_THROW(ids::objectFeatureId(INT32_MAX, 0), std::out_of_range);
	EXPECT_THROW(ids::objectFeatureId(0, -1), std::out_of_range);
	EXPECT_THROW(ids::objectFeatureId(0, ids::kFeaturesPerObject), std::out_of_range);
}

TEST(LandmarkIds, Describe)
{
	EXPECT_EQ(ids::describe(12), "static landmark 12");
	EXPECT_EQ(ids::describe(0), "static landmark 0");
	EXPECT_EQ(ids::describe(101'003), "object 1 feature 3");
	EXPECT_EQ(ids::describe(ids::objectFeatureId(42, 7)), "object 42 feature 7");
	EXPECT_EQ(ids::describe(-1), "invalid landmark ID -1");
}
