// TUM, per-step CSV, metrics CSV writers.
#include <dynslam/eval/writers.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "eval_test_data.h"

using namespace dynslam::eval;

namespace
{
std::vector<std::string> lines(const std::string& s)
{
	std::vector<std::string> v;
	std::istringstream is(s);
	std::string l;
	while (std::getline(is, l)) v.push_back(l);
	return v;
}

TRunEstimates smallRun()
{
	TRunEstimates est;
	for (int k : {1, 0})
	{
		TEgoEstimate e;
		e.step = k;
		e.mean = Eigen::Vector3d(k, 0.5 * k, k == 1 ? M_PI / 2 : 0.0);
		e.cov = 0.01 * Eigen::Matrix3d::Identity();
		est.ego.push_back(e);
	}
	est.nis = {0.0, 3.5};
	est.nis_dof = {0, 4};
	est.landmarks.push_back({2, {20.3, -5}, 0.04 * Eigen::Matrix2d::Identity()});
	est.landmarks.push_back({77, {1, 1}, 0.04 * Eigen::Matrix2d::Identity()});
	TObjectPoseEstimate p;
	p.object = 1;
	p.step = 2;
	p.mean = Eigen::Vector2d(0.1, 1.0);
	p.cov = 0.01 * Eigen::Matrix2d::Identity();
	est.object_poses.push_back(p);
	est.object_features.push_back({0, 1, {8, 2.5}, 0.01 * Eigen::Matrix2d::Identity()});
	est.ms_per_step = 0.25;
	return est;
}
}  // namespace

TEST(Writers, TumUsesTimesAndYawQuaternion)
{
	const auto gt = eval_test::smallGroundTruth();
	const auto est = smallRun();
	std::ostringstream os;
	writeTum(os, est.ego, &gt);
	const auto l = lines(os.str());
	ASSERT_EQ(l.size(), 2u);
	EXPECT_EQ(l[0], "0 0 0 0 0 0 0 1");
	double t, x, y, z, qx, qy, qz, qw;
	std::istringstream(l[1]) >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
	EXPECT_DOUBLE_EQ(t, 0.5);
	EXPECT_DOUBLE_EQ(x, 1.0);
	EXPECT_NEAR(qz, std::sqrt(0.5), 1e-9);
	EXPECT_NEAR(qw, std::sqrt(0.5), 1e-9);
	std::ostringstream bad;
	EXPECT_THROW(writeTum(bad, est.ego, nullptr), std::invalid_argument);
}

TEST(Writers, EgoCsvWithTruthSigmaAndNis)
{
	const auto gt = eval_test::smallGroundTruth();
	std::ostringstream os;
	writeEgoCsv(os, smallRun(), &gt);
	const auto l = lines(os.str());
	ASSERT_EQ(l.size(), 3u);
	EXPECT_EQ(l[0],
	          "step,t,x,y,theta,sigma3_x,sigma3_y,sigma3_theta,gt_x,gt_y,gt_theta,err_x,err_y,"
	          "err_theta,nees,nis,nis_dof");
	EXPECT_EQ(l[1], "0,0,0,0,0,0.3,0.3,0.3,0,0,0,0,0,0,0,,0");
	// Step 1: truth (1, 0, 0.1), estimate (1, 0.5, pi/2).
	EXPECT_EQ(l[2].rfind("1,0.5,1,0.5,1.57079633,0.3,0.3,0.3,1,0,0.1,0,0.5,1.47079633,", 0), 0u)
	    << l[2];
	EXPECT_NE(l[2].find(",3.5,4"), std::string::npos);
	// Without ground truth the truth columns stay empty.
	std::ostringstream os2;
	writeEgoCsv(os2, smallRun(), nullptr);
	EXPECT_EQ(lines(os2.str())[1], "0,,0,0,0,0.3,0.3,0.3,,,,,,,,,0");  // no t, no truth
}

TEST(Writers, LandmarkObjectCsv)
{
	const auto gt = eval_test::smallGroundTruth();
	std::ostringstream os;
	writeLandmarksCsv(os, smallRun(), &gt);
	auto l = lines(os.str());
	ASSERT_EQ(l.size(), 3u);
	EXPECT_EQ(l[1], "2,20.3,-5,0.6,0.6,20,-5,0.3,0,2.25");
	EXPECT_EQ(l[2], "77,1,1,0.6,0.6,,,,,");
	std::ostringstream op;
	writeObjectPosesCsv(op, smallRun(), &gt);
	l = lines(op.str());
	ASSERT_EQ(l.size(), 2u);
	EXPECT_EQ(l[1], "1,2,1,0.1,1,,0.3,0.3,,0,1,0,0.1,0,,1,2");
	std::ostringstream of;
	writeObjectFeaturesCsv(of, smallRun(), &gt);
	l = lines(of.str());
	ASSERT_EQ(l.size(), 2u);
	EXPECT_EQ(l[1], "0,1,8,2.5,0.3,0.3,8,2,0,0.5");  // object 0 first seen at step 1: (8, 2)
}

TEST(Writers, MetricsCsvHasRequiredColumnsAndOneRowPerFilter)
{
	const auto gt = eval_test::smallGroundTruth();
	const auto est = smallRun();
	std::vector<TMetricsRow> rows;
	rows.push_back({"static_all", computeRunMetrics(gt, est), std::nullopt, std::nullopt,
	                std::nullopt, std::nullopt, std::nullopt, std::nullopt});
	rows.push_back({"dynamic", computeRunMetrics(gt, est),
	                summarizeConsistency({computeRunConsistency(gt, est)}), std::nullopt,
	                std::nullopt, std::nullopt, std::nullopt, std::nullopt});
	std::ostringstream os;
	writeMetricsCsv(os, rows);
	const auto l = lines(os.str());
	ASSERT_EQ(l.size(), 3u);
	EXPECT_EQ(l[0].rfind("filter,ego_rmse_x,ego_rmse_y,ego_rmse_theta,static_rmse_x,static_rmse_y,"
	                     "ate,ate_aligned,ms_per_step,",
	                     0),
	          0u);
	EXPECT_NE(l[0].find("agent2_pose_rmse_theta"), std::string::npos);
	const auto commas = std::count(l[0].begin(), l[0].end(), ',');
	for (const auto& r : l) EXPECT_EQ(std::count(r.begin(), r.end(), ','), commas) << r;
	// Ego errors: step 0 (0, 0, 0), step 1 (0, 0.5, pi/2 - 0.1); landmark 2 error (0.3, 0).
	// Aligned ATE of two points: half the length difference (sqrt(1.25) - 1) / 2 = 0.0590169944.
	EXPECT_EQ(
	    l[1].rfind(
	        "static_all,0,0.353553391,1.04001006,0.3,0,0.353553391,0.0590169944,0.25,2,1,2,1,", 0),
	    0u)
	    << l[1];
	EXPECT_NEAR((M_PI / 2 - 0.1) / std::sqrt(2.0), 1.04001006, 1e-8);
	// no bias state: the two bias columns are the last two and empty
	EXPECT_EQ(l[0].substr(l[0].size() - 51), ",odometry_bias_rate_final,odometry_bias_scale_final");
	EXPECT_EQ(l[1].substr(l[1].size() - 2), ",,");
	EXPECT_EQ(l[2].substr(l[2].size() - 2), ",,");
	std::ostringstream table;
	writeMetricsTable(table, rows);
	EXPECT_EQ(lines(table.str()).size(), 3u);
	std::ostringstream sum;
	writeConsistencySummary(sum, *rows[1].consistency);
	EXPECT_NE(sum.str().find("ego"), std::string::npos);
	std::ostringstream csv;
	writeConsistencySummaryCsv(csv, {{"w1v1", *rows[1].consistency}});
	const auto c = lines(csv.str());
	// Header, ego, landmarks, map, object 1 pose (the only object with a pose), nis.
	ASSERT_EQ(c.size(), 6u);
	EXPECT_EQ(c[1].rfind("w1v1,ego,1,2,", 0), 0u) << c[1];
	EXPECT_EQ(c[4].rfind("w1v1,object1_pose,1,1,", 0), 0u) << c[4];
	EXPECT_EQ(c[5].rfind("w1v1,nis,1,1,", 0), 0u) << c[5];
}

TEST(Writers, MetricsCsvCarriesTheFinalOdometryBias)
{
	const auto gt = eval_test::smallGroundTruth();
	auto est = smallRun();
	est.odometry_bias = Eigen::Vector2d(0.0175, -0.03);
	std::vector<TMetricsRow> rows{{"rate_scale", computeRunMetrics(gt, est), std::nullopt,
	                               std::nullopt, std::nullopt, std::nullopt, std::nullopt,
	                               std::nullopt}};
	est.odometry_bias = Eigen::VectorXd::Constant(1, -0.002);
	rows.push_back({"rate", computeRunMetrics(gt, est), std::nullopt, std::nullopt, std::nullopt,
	                std::nullopt, std::nullopt, std::nullopt});
	EXPECT_EQ(rows[0].metrics.odometry_bias_rate, 0.0175);
	EXPECT_EQ(rows[0].metrics.odometry_bias_scale, -0.03);
	EXPECT_TRUE(std::isnan(rows[1].metrics.odometry_bias_scale));
	std::ostringstream os;
	writeMetricsCsv(os, rows);
	const auto l = lines(os.str());
	ASSERT_EQ(l.size(), 3u);
	EXPECT_EQ(l[1].substr(l[1].size() - 13), ",0.0175,-0.03") << l[1];
	EXPECT_EQ(l[2].substr(l[2].size() - 8), ",-0.002,") << l[2];
}
