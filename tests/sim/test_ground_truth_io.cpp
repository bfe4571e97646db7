/** Ground-truth files (libs/core ground_truth.h): exact round trip and strict reading. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/io/ground_truth.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "sim_test_utils.h"

namespace io = dynslam::io;

namespace
{
io::TGroundTruth randomGroundTruth()
{
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> u(-500, 500);
	io::TGroundTruth gt;
	const size_t n = 9;
	for (size_t k = 0; k < n; ++k)
	{
		gt.t.push_back(0.5 * k);
		gt.ego.emplace_back(u(rng), u(rng), u(rng) / 500 * M_PI);
	}
	for (int id : {0, 3, 99999}) gt.landmarks[id] = Eigen::Vector2d(u(rng), u(rng) / 3);
	for (int obj = 0; obj < 2; ++obj)
	{
		dynslam::io::TObjectGroundTruth o;
		o.object = obj;
		o.num_features = obj == 0 ? 4 : 1;
		o.first_step = obj == 0 ? 2 : -1;
		for (size_t k = 0; k < n; ++k)
		{
			Eigen::Matrix2Xd F(2, o.num_features);
			for (int j = 0; j < o.num_features; ++j) F.col(j) << u(rng), u(rng);
			o.features.push_back(F);
			const bool seen = o.first_step >= 0 && int(k) >= o.first_step;
			o.pose.push_back(
			    seen ? Eigen::Vector3d(u(rng), u(rng), 0.1 * k)
			         : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
			o.visible.push_back(seen && k % 3 != 0);
		}
		gt.objects.push_back(o);
	}
	return gt;
}

std::string tmpDir(const std::string& name)
{
	const auto d = std::filesystem::path(DYNSLAM_BINARY_DIR) / "test_tmp" / name;
	std::filesystem::remove_all(d);
	std::filesystem::create_directories(d);
	return d.string();
}

bool sameOrBothNaN(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }
}  // namespace

TEST(SimGroundTruthIO, RoundTripIsExact)
{
	const io::TGroundTruth gt = randomGroundTruth();
	const std::string dir = tmpDir("gt_roundtrip");
	dynslam::io::writeGroundTruth(gt, dir, "rt");
	const io::TGroundTruth back = dynslam::io::readGroundTruth(dir, "rt");
	ASSERT_EQ(back.numSteps(), gt.numSteps());
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		EXPECT_EQ(back.t[k], gt.t[k]);
		EXPECT_EQ(back.ego[k], gt.ego[k]);
	}
	ASSERT_EQ(back.landmarks.size(), gt.landmarks.size());
	for (const auto& [id, p] : gt.landmarks) EXPECT_EQ(back.landmarks.at(id), p);
	ASSERT_EQ(back.objects.size(), gt.objects.size());
	for (size_t i = 0; i < gt.objects.size(); ++i)
	{
		const auto &a = gt.objects[i], &b = back.objects[i];
		EXPECT_EQ(b.object, a.object);
		EXPECT_EQ(b.num_features, a.num_features);
		EXPECT_EQ(b.first_step, a.first_step);
		EXPECT_EQ(b.visible, a.visible);
		for (size_t k = 0; k < gt.numSteps(); ++k)
		{
			EXPECT_EQ(b.features[k], a.features[k]);
			for (int c = 0; c < 3; ++c) EXPECT_TRUE(sameOrBothNaN(b.pose[k][c], a.pose[k][c]));
		}
	}
	// TUM file: 8 columns per line, quaternion of the heading.
	std::ifstream tum(dir + "/rt_gt_ego.tum");
	std::string line;
	std::getline(tum, line);
	EXPECT_EQ(line[0], '#');
	double t, x, y, z, qx, qy, qz, qw;
	tum >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
	EXPECT_EQ(x, gt.ego[0][0]);
	EXPECT_NEAR(2 * std::atan2(qz, qw), gt.ego[0][2], 1e-15);
}

TEST(SimGroundTruthIO, MalformedFilesAreRejectedWithFileAndLine)
{
	const io::TGroundTruth gt = randomGroundTruth();
	const std::string dir = tmpDir("gt_bad");
	dynslam::io::writeGroundTruth(gt, dir, "b");
	const std::string ego = dir + "/b_gt_ego.csv";
	const std::string good = dynslam_test::readFile(ego);
	auto expectError = [&](const std::string& content, const std::string& needle)
	{
		std::ofstream(ego, std::ios::binary) << content;
		try
		{
			dynslam::io::readGroundTruth(dir, "b");
			ADD_FAILURE() << "accepted: " << needle;
		}
		catch (const std::runtime_error& e)
		{
			const std::string msg = e.what();
			EXPECT_NE(msg.find("b_gt_ego.csv"), std::string::npos) << msg;
			EXPECT_NE(msg.find(needle), std::string::npos) << msg;
		}
	};
	expectError("step,t,x,y\n0,0,1,2\n", "header");
	expectError("step,t,x,y,theta\n0,0,1,2,0\n1,0.5,abc,2,0\n", ":3: field 'abc'");
	expectError("step,t,x,y,theta\n0,0,1,2\n", ":2: 4 fields");
	expectError("step,t,x,y,theta\n0,0,1,2,0\n2,0.5,1,2,0\n", ":3: step 2 out of sequence");
	std::ofstream(ego, std::ios::binary) << good;
	EXPECT_NO_THROW(dynslam::io::readGroundTruth(dir, "b"));
	std::filesystem::remove(dir + "/b_gt_objects.csv");
	EXPECT_THROW(dynslam::io::readGroundTruth(dir, "b"), std::runtime_error);
}

TEST(SimGroundTruthIO, InconsistentGroundTruthIsNotWritten)
{
	io::TGroundTruth gt = randomGroundTruth();
	gt.objects[0].pose.pop_back();
	EXPECT_THROW(dynslam::io::writeGroundTruth(gt, tmpDir("gt_inconsistent"), "x"),
	             std::runtime_error);
	gt = randomGroundTruth();
	gt.landmarks[dynslam::ids::kObjectBase] = Eigen::Vector2d::Zero();
	EXPECT_THROW(gt.checkConsistent(), std::runtime_error);
}
