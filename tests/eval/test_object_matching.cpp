/** eval::matchObjectsByReadings and the object velocity scores of classifying rows
 * (doc/metrics.md "Objects of classifying rows"): the router numbers its objects in another
 * order than the truth, so matching by number compares the wrong objects. */
#include <dynslam/eval/object_matching.h>
#include <dynslam/eval/writers.h>
#include <gtest/gtest.h>
#include <velocity_estimate.h>

#include <cmath>
#include <sstream>

using namespace dynslam;
using namespace dynslam::eval;

namespace
{
/** True objects 0 and 1 at constant velocities (1, 0) and (0, 2) m/s, dt = 0.5 s, 5 steps. */
io::TGroundTruth twoObjects()
{
	io::TGroundTruth gt;
	const Eigen::Vector2d v[2] = {{1, 0}, {0, 2}};
	for (int j = 0; j < 2; ++j)
	{
		io::TObjectGroundTruth o;
		o.object = j;
		for (int k = 0; k < 5; ++k) o.pose.emplace_back(v[j].x() * 0.5 * k, v[j].y() * 0.5 * k, 0);
		gt.objects.push_back(o);
	}
	for (int k = 0; k < 5; ++k)
	{
		gt.t.push_back(0.5 * k);
		gt.ego.emplace_back(0, 0, 0);
	}
	return gt;
}

io::TReadingClass reading(int32_t object)
{
	io::TReadingClass r;
	r.cls = object < 0 ? io::TrueClass::Static : io::TrueClass::Moving;
	r.object = object;
	return r;
}

/** Velocity v (unit variances) of object `obj` at `step`. */
TObjectPoseEstimate velocityOf(int32_t obj, int step, const Eigen::Vector2d& v)
{
	return eval_test::withVelocity(obj, step, v, Eigen::Vector2d::Ones());
}

/** The router's numbering: estimated object 0 is true object 1 (3 of its 4 readings), 1 is
 * true object 0; 2 is mostly static readings (no true match). */
struct TSwapped
{
	std::vector<int32_t> est{0, 0, 0, 0, 1, 1, 2, 2, 2, -1};
	std::vector<io::TReadingClass> truth{reading(1), reading(1), reading(1),  reading(0),
	                                     reading(0), reading(0), reading(-1), reading(-1),
	                                     reading(1), reading(-1)};
};
}  // namespace

TEST(ObjectMatching, MajorityOfTheReadingsTiesAndNoMatch)
{
	const TSwapped s;
	const auto m = matchObjectsByReadings(s.est, s.truth);
	ASSERT_EQ(m.size(), 3u);
	EXPECT_EQ(m.at(0), 1);
	EXPECT_EQ(m.at(1), 0);
	EXPECT_EQ(m.at(2), -1);  // 2 static readings beat 1 of object 1
	// A tie between two true objects: the smaller; a tie with "no object": the object.
	const auto t =
	    matchObjectsByReadings({4, 4, 5, 5}, {reading(1), reading(0), reading(-1), reading(1)});
	EXPECT_EQ(t.at(4), 0);
	EXPECT_EQ(t.at(5), 1);
	EXPECT_THROW(matchObjectsByReadings({0}, {}), std::invalid_argument);
}

TEST(ObjectMatching, ClassifyingSpeedErrorIsThatOfTheMatchedTrueObject)
{
	const io::TGroundTruth gt = twoObjects();
	TRunEstimates est;
	// Estimated 0 (true 1, v = (0, 2)) off by (0.3, 0.4): 0.5 m/s; estimated 1 (true 0,
	// v = (1, 0)) off by (0.6, 0.8): 1 m/s; estimated 2 has no true object (skipped).
	for (int k = 1; k < 4; ++k)
	{
		est.object_poses.push_back(velocityOf(0, k, {0.3, 2.4}));
		est.object_poses.push_back(velocityOf(1, k, {1.6, 0.8}));
		est.object_poses.push_back(velocityOf(2, k, {5, 5}));
	}
	const TSwapped s;
	const auto v = classifyingVelocityErrors(gt, est, s.est, &s.truth);
	ASSERT_TRUE(v);
	const double expected = std::sqrt((3 * 0.25 + 3 * 1.0) / 6);  // independent: by hand
	EXPECT_NEAR(v->speed_rmse, expected, 1e-12);
	EXPECT_EQ(v->n, 6u);
	EXPECT_EQ(v->skipped, 3u);
	EXPECT_NEAR(v->speed_rmse_per_object.at(1), 0.5, 1e-12);
	EXPECT_NEAR(v->speed_rmse_per_object.at(0), 1.0, 1e-12);
	// By number (the old scoring) the same run gives another value: the test cannot pass by
	// accident.
	const auto byIndex = objectVelocityErrors(gt, est);
	ASSERT_TRUE(byIndex);
	EXPECT_GT(std::abs(byIndex->speed_rmse - expected), 0.5);
	// Two estimated objects on one true object (a track break): each scored against it.
	TRunEstimates broken;
	broken.object_poses = {velocityOf(7, 1, {1.3, 0.4}), velocityOf(8, 3, {1, 0})};
	const std::vector<io::TReadingClass> tr{reading(0), reading(0)};
	const auto b = classifyingVelocityErrors(gt, broken, {7, 8}, &tr);
	ASSERT_TRUE(b);
	EXPECT_EQ(b->n, 2u);
	EXPECT_NEAR(b->speed_rmse, std::sqrt(0.25 / 2), 1e-12);
}

TEST(ObjectMatching, WithoutClassTruthTheCellsAreEmpty)
{
	const io::TGroundTruth gt = twoObjects();
	TRunEstimates est;
	est.object_poses.push_back(velocityOf(0, 1, {0, 2}));
	EXPECT_FALSE(classifyingVelocityErrors(gt, est, {0}, nullptr));
	TMetricsRow plain, classifying;
	plain.filter = "dynamic_cv";
	plain.velocity = objectVelocityErrors(gt, est);
	classifying.filter = "dynamic_classified";
	classifying.velocity = classifyingVelocityErrors(gt, est, {0}, nullptr);
	TObjectMetrics om;
	om.object = 1;
	om.poses.x = om.poses.y = 0.5;
	classifying.metrics.objects.push_back(om);
	blankObjectColumns(classifying.metrics);
	EXPECT_EQ(classifying.metrics.objects[0].object, 1);
	EXPECT_TRUE(std::isnan(classifying.metrics.objects[0].poses.x));
	std::ostringstream os;
	writeMetricsCsv(os, {plain, classifying});
	const std::string csv = os.str();
	const std::string last = csv.substr(csv.rfind("dynamic_classified"));
	EXPECT_EQ(last.substr(last.size() - 5), ",,,,\n") << csv;
	EXPECT_NE(last.find(",1,,,,,,"), std::string::npos) << csv;  // agent_1: object, empty RMSEs
}
