/** Ground truth of the highway and of generated scenarios: start pose, smoothness, object
 * poses g^o(xi_t, f_0) = f_t, determinism. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>

#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam::sim;

namespace
{
TScenarioOptions configOptions(const std::string& file)
{
	return loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/" + file);
}

/** g^o(xi_k, f_first) = f_k for every object and every step after its first sighting. */
void expectObjectPosesExact(const dynslam::io::TGroundTruth& gt, double* maxErrOut = nullptr)
{
	double maxErr = 0;
	for (const auto& og : gt.objects)
	{
		if (og.first_step < 0)
		{
			for (const auto& xi : og.pose) EXPECT_TRUE(xi.array().isNaN().all());
			continue;
		}
		const Eigen::Matrix2Xd& F0 = og.features[og.first_step];
		for (size_t k = 0; k < gt.numSteps(); ++k)
		{
			if (int(k) < og.first_step)
			{
				EXPECT_TRUE(og.pose[k].array().isNaN().all());
				continue;
			}
			Eigen::Matrix2Xd Fk;
			if (og.translationOnly())
			{
				EXPECT_EQ(og.pose[k][2], 0);
				Fk = F0.colwise() + og.pose[k].head<2>();
			}
			else
				Fk = dynslam::models::objectPoseMap(og.pose[k], F0);
			const double scale = std::max(1.0, og.features[k].cwiseAbs().maxCoeff());
			const double err = (Fk - og.features[k]).cwiseAbs().maxCoeff() / scale;
			maxErr = std::max(maxErr, err);
		}
		EXPECT_EQ(og.pose[og.first_step].norm(), og.pose[og.first_step].norm());  // not NaN
		EXPECT_LT(og.pose[og.first_step].norm(), 1e-12);
	}
	// Relative to the coordinates' magnitude: a few ulp.
	EXPECT_LT(maxErr, 1e-14);
	if (maxErrOut) *maxErrOut = maxErr;
}
}  // namespace

TEST(SimGroundTruth, HighwayLayout)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	ASSERT_EQ(gt.numSteps(), 121u);
	EXPECT_EQ(gt.ego[0], Eigen::Vector3d::Zero());  // world frame = ego start pose
	// Ground-truth time = the rawlog's time stamps: start_time + k dt.
	EXPECT_EQ(gt.t[0], o.start_time);
	EXPECT_EQ(gt.t[120], o.start_time + 60.0);
	EXPECT_EQ(o.start_time, 1.6e9);
	EXPECT_GT(gt.ego.back()[0], 950);  // about 1 km in 60 s
	EXPECT_LT(gt.ego.back()[0], 1050);
	EXPECT_EQ(gt.landmarks.size(), size_t(o.highway.num_landmarks));
	ASSERT_EQ(gt.objects.size(), 3u);
	EXPECT_EQ(gt.objects[0].num_features, 4);
	EXPECT_EQ(gt.objects[1].num_features, 4);
	EXPECT_EQ(gt.objects[2].num_features, 2);
	const THighwayOptions& h = o.highway;
	for (const auto& [id, p] : gt.landmarks)
	{
		EXPECT_TRUE(dynslam::ids::isStatic(id));
		const double off = p[1] > 0 ? p[1] - h.roadLeft() : h.roadRight() - p[1];
		EXPECT_GE(off, h.landmark_offset_min);
		EXPECT_LE(off, h.landmark_offset_max);
		EXPECT_GE(p[0], 0);
		EXPECT_LE(p[0], h.length);
	}
	// Cars stay on the road; the pedestrian starts on one side and ends on the other.
	for (int i : {0, 1})
		for (const auto& F : gt.objects[i].features)
		{
			EXPECT_LE(F.row(1).maxCoeff(), h.roadLeft());
			EXPECT_GE(F.row(1).minCoeff(), h.roadRight());
		}
	const auto& ped = gt.objects[2].features;
	EXPECT_LT(ped.front().row(1).mean(), h.roadRight());
	EXPECT_GT(ped.back().row(1).mean(), h.roadLeft());
	// Every agent is seen, and landmarks enter and leave view (some are never in view at k=0).
	for (const auto& og : gt.objects) EXPECT_GE(og.first_step, 0);
	int seenAtStart = 0;
	for (const auto& [id, p] : gt.landmarks)
		seenAtStart += (p - gt.ego[0].head<2>()).norm() <= o.sensor_range;
	EXPECT_GT(seenAtStart, 0);
	EXPECT_LT(seenAtStart, int(gt.landmarks.size()) / 4);
}

TEST(SimGroundTruth, TrajectoriesAreSmooth)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	// No teleporting: the displacement per step is bounded by the top speed, and the
	// acceleration (second difference) by a few m/s^2.
	auto check = [&](auto positionAt, const std::string& what, double maxAccel)
	{
		for (size_t k = 2; k < gt.numSteps(); ++k)
		{
			const Eigen::Vector2d a = positionAt(k - 2), b = positionAt(k - 1), c = positionAt(k);
			EXPECT_LT((c - b).norm(), 25.0 * o.dt) << what << " k " << k;
			EXPECT_LT((c - 2 * b + a).norm() / (o.dt * o.dt), maxAccel) << what << " k " << k;
		}
	};
	check([&](size_t k) { return Eigen::Vector2d(gt.ego[k].head<2>()); }, "ego", 3.0);
	for (const auto& og : gt.objects)
		check([&](size_t k) { return Eigen::Vector2d(og.features[k].rowwise().mean()); },
		      "object " + std::to_string(og.object), 3.0);
	for (size_t k = 1; k < gt.numSteps(); ++k)
		EXPECT_LT(std::abs(dynslam::models::wrapToPi(gt.ego[k][2] - gt.ego[k - 1][2])), 0.1);
}

TEST(SimGroundTruth, ObjectPosesReproduceFeaturesToMachinePrecision)
{
	for (const std::string file :
	     {"highway.ini", "generated_small_scenario.ini", "generated_circle_scenario.ini"})
	{
		SCOPED_TRACE(file);
		const TScenarioOptions o = configOptions(file);
		double err = 0;
		expectObjectPosesExact(buildGroundTruth(o), &err);
		std::cout << "[          ] " << file << ": max |g^o(xi_k, f_0) - f_k| / max|f_k| = " << err
		          << "\n";
	}
}

TEST(SimGroundTruth, VisibilityFollowsTheSensorModel)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	for (const auto& og : gt.objects)
		for (size_t k = 0; k < gt.numSteps(); ++k)
		{
			const double d = (og.features[k].rowwise().mean() - gt.ego[k].head<2>()).norm();
			EXPECT_EQ(og.visible[k] != 0, d <= o.sensor_range);
			if (og.visible[k])
			{
				EXPECT_GE(int(k), og.first_step);
			}
		}
}

TEST(SimGroundTruth, DeterministicGivenTheWorldSeed)
{
	TScenarioOptions o = configOptions("generated_small_scenario.ini");
	const dynslam::io::TGroundTruth a = buildGroundTruth(o), b = buildGroundTruth(o);
	ASSERT_EQ(a.landmarks.size(), b.landmarks.size());
	for (const auto& [id, p] : a.landmarks) EXPECT_EQ(b.landmarks.at(id), p);
	for (size_t i = 0; i < a.objects.size(); ++i)
		for (size_t k = 0; k < a.numSteps(); ++k)
			EXPECT_EQ(a.objects[i].features[k], b.objects[i].features[k]);
	o.world_seed += 1;
	const dynslam::io::TGroundTruth c = buildGroundTruth(o);
	EXPECT_NE(c.landmarks.at(0), a.landmarks.at(0));
	o.world_seed = 0;  // seed 0 is a seed like any other (not time-seeded)
	const dynslam::io::TGroundTruth z1 = buildGroundTruth(o), z2 = buildGroundTruth(o);
	EXPECT_EQ(z1.landmarks.at(5), z2.landmarks.at(5));
}

TEST(SimGroundTruth, GeneratedScenarios)
{
	const TScenarioOptions o = configOptions("generated_small_scenario.ini");
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const TGeneratedOptions& g = o.generated;
	EXPECT_EQ(gt.numSteps(), size_t(o.steps) + 1);
	EXPECT_EQ(gt.landmarks.size(), size_t(g.num_landmarks));
	ASSERT_EQ(gt.objects.size(), size_t(g.num_cars + g.num_pedestrians + g.num_rotating));
	EXPECT_EQ(gt.ego[0], Eigen::Vector3d::Zero());
	EXPECT_NEAR(gt.ego.back()[0], g.ego_speed * o.steps * o.dt, 1e-9);
	for (int i = 0; i < g.num_cars; ++i) EXPECT_EQ(gt.objects[i].num_features, g.features_per_car);
	for (int i = 0; i < g.num_pedestrians; ++i)
		EXPECT_TRUE(gt.objects[g.num_cars + i].translationOnly());  // features_per_pedestrian = 1
	// Rotating objects stay in place and turn.
	for (int i = 0; i < g.num_rotating; ++i)
	{
		const auto& og = gt.objects[g.num_cars + g.num_pedestrians + i];
		EXPECT_EQ(og.num_features, g.features_per_rotating);
		EXPECT_LT(
		    (og.features.back().rowwise().mean() - og.features.front().rowwise().mean()).norm(),
		    1e-9);
		if (og.first_step >= 0 && og.first_step + 4 < int(gt.numSteps()))
		{
			EXPECT_GT(std::abs(og.pose[og.first_step + 4][2]), 0.1 * 4 * o.dt * 0.99);
		}
	}
	// Circle: the ego comes back near the start after one lap.
	const TScenarioOptions c = configOptions("generated_circle_scenario.ini");
	const dynslam::io::TGroundTruth gc = buildGroundTruth(c);
	const double lapTime = 2 * M_PI * c.generated.track_radius / c.generated.ego_speed;
	const size_t kLap = size_t(std::lround(lapTime / c.dt));
	ASSERT_LT(kLap, gc.numSteps());
	EXPECT_LT(gc.ego[kLap].head<2>().norm(), c.generated.ego_speed * c.dt);
	for (const auto& x : gc.ego)
		EXPECT_NEAR((x.head<2>() - Eigen::Vector2d(0, c.generated.track_radius)).norm(),
		            c.generated.track_radius, 1e-9);
}

TEST(SimGroundTruth, LandmarkGapsRemoveOnlyTheLandmarksInside)
{
	// Highway (x along the road) and a straight generated track (x = arc length - its start):
	// the landmarks outside the gaps are exactly those without gaps (same draws).
	for (const char* file : {"highway.ini", "generated_small_scenario.ini"})
	{
		TScenarioOptions o = configOptions(file);
		const dynslam::io::TGroundTruth all = buildGroundTruth(o);
		o.landmark_gaps = {{200, 450}, {600, 650}};
		const dynslam::io::TGroundTruth gapped = buildGroundTruth(o);
		size_t inside = 0;
		for (const auto& [id, f] : all.landmarks)
		{
			if (o.inLandmarkGap(f[0]))
			{
				++inside;
				EXPECT_EQ(gapped.landmarks.count(id), 0u) << file << " landmark " << id;
			}
			else
			{
				ASSERT_EQ(gapped.landmarks.count(id), 1u) << file << " landmark " << id;
				EXPECT_EQ(gapped.landmarks.at(id), f);
			}
		}
		EXPECT_GT(inside, 0u) << file;
		EXPECT_EQ(gapped.landmarks.size(), all.landmarks.size() - inside) << file;
	}
	// Read from the INI, written back by the dump, bad lists rejected naming the key.
	const TScenarioOptions t = configOptions("tunnel.ini");
	ASSERT_EQ(t.landmark_gaps.size(), 1u);
	EXPECT_EQ(t.landmark_gaps[0], std::make_pair(200.0, 800.0));
	std::ostringstream dump;
	t.dumpToTextStream(dump);
	EXPECT_EQ(loadScenarioFromText(dump.str()).landmark_gaps, t.landmark_gaps);
	std::string bad = dump.str();
	const auto at = bad.find("landmark_gaps = [200 800]");
	ASSERT_NE(at, std::string::npos) << bad;
	for (const char* v :
	     {"landmark_gaps = [350]", "landmark_gaps = [650 350]", "landmark_gaps = [350 x]"})
	{
		std::string b = bad;
		b.replace(at, std::string("landmark_gaps = [200 800]").size(), v);
		try
		{
			loadScenarioFromText(b);
			ADD_FAILURE() << v << " accepted";
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("landmark_gaps"), std::string::npos) << e.what();
		}
	}
}
