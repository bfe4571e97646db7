/** Scenario INI reading: the shipped configs load, bad input is rejected naming the key. */
#include <dynslam/sim/TScenarioOptions.h>
#include <dynslam_test/temp_dir.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam::sim;
using dynslam_test::readFile;
using dynslam_test::removeIniKey;
using dynslam_test::setIniKey;

namespace
{
/** Expects loading `ini` to throw std::invalid_argument whose message contains all needles. */
void expectRejected(const std::string& ini, const std::vector<std::string>& needles)
{
	try
	{
		loadScenarioFromText(ini);
		ADD_FAILURE() << "accepted, expected an error naming " << needles.front();
	}
	catch (const std::invalid_argument& e)
	{
		const std::string msg = e.what();
		for (const auto& n : needles)
			EXPECT_NE(msg.find(n), std::string::npos) << "message: " << msg;
	}
}
}  // namespace

TEST(SimOptions, HighwayIniLoadsWithDocumentedValues)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	EXPECT_EQ(o.type, ScenarioType::Highway);
	EXPECT_EQ(o.name, "highway");
	EXPECT_EQ(o.dt, 0.5);
	EXPECT_EQ(o.steps, 120);
	EXPECT_EQ(o.numSteps(), 121u);
	EXPECT_EQ(o.highway.length, 1000);
	EXPECT_EQ(o.highway.num_lanes, 3);
	EXPECT_EQ(o.highway.laneY(o.highway.ego_lane), 0);
	ASSERT_EQ(o.highway.agents.size(), 3u);
	EXPECT_EQ(o.highway.agents[0].kind, THighwayAgent::Kind::Car);
	EXPECT_EQ(o.highway.agents[1].kind, THighwayAgent::Kind::Car);
	EXPECT_EQ(o.highway.agents[2].kind, THighwayAgent::Kind::Pedestrian);
	EXPECT_EQ(o.noise_level, "w2v2");
	EXPECT_EQ(o.Sigma_w, Eigen::Vector3d(1e-5, 1e-5, 1e-7).asDiagonal().toDenseMatrix());
	EXPECT_EQ(o.Sigma_v, (1e-5 * Eigen::Matrix2d::Identity()).eval());
	EXPECT_EQ(o.Sigma_0, o.Sigma_w);
	EXPECT_DOUBLE_EQ(o.std_range, std::sqrt(1e-5));
	EXPECT_DOUBLE_EQ(o.std_yaw, std::sqrt(1e-5) / (o.sensor_range / 2));
}

TEST(SimOptions, NoiseGridOfThePaper)
{
	for (int w = 1; w <= 3; ++w)
		for (int v = 1; v <= 3; ++v)
		{
			const std::string name = "w" + std::to_string(w) + "v" + std::to_string(v);
			const TNoiseLevel n = noiseLevel(name);
			const double sw = std::pow(10.0, -7 + w), sv = std::pow(10.0, -7 + v);
			EXPECT_DOUBLE_EQ(n.Sigma_w(0, 0), sw) << name;
			EXPECT_DOUBLE_EQ(n.Sigma_w(1, 1), sw) << name;
			EXPECT_DOUBLE_EQ(n.Sigma_w(2, 2), sw * 1e-2) << name;
			const double exact[] = {1e-6, 1e-5, 1e-4};  // the literals of eq. (5)-(7)
			EXPECT_EQ(n.Sigma_w(0, 0), exact[w - 1]);
			EXPECT_EQ(n.Sigma_v(0, 0), exact[v - 1]);
			EXPECT_EQ(n.Sigma_w(0, 1), 0);
			EXPECT_DOUBLE_EQ(n.Sigma_v(0, 0), sv) << name;
			EXPECT_DOUBLE_EQ(n.Sigma_v(1, 1), sv) << name;
		}
	EXPECT_EQ(noiseLevel("none").Sigma_w.norm(), 0);
	EXPECT_NO_THROW(noiseLevel("W3V1"));
	EXPECT_THROW(noiseLevel("w4v1"), std::invalid_argument);
	EXPECT_THROW(noiseLevel("w1"), std::invalid_argument);
}

TEST(SimOptions, DumpReloadsToTheSameOptions)
{
	for (const std::string file : {"highway.ini", "highway_static_scenario.ini",
	                               "generated_small_scenario.ini", "generated_circle_scenario.ini"})
	{
		const TScenarioOptions o = loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/" + file);
		std::ostringstream a, b;
		o.dumpToTextStream(a);
		const TScenarioOptions o2 = loadScenarioFromText(a.str());
		o2.dumpToTextStream(b);
		EXPECT_EQ(a.str(), b.str()) << file;
		EXPECT_EQ(o2.Sigma_0, o.Sigma_0);
		EXPECT_EQ(o2.start_time, o.start_time);
	}
}

TEST(SimOptions, BadIniIsRejectedNamingTheKey)
{
	const std::string ini = readFile(dynslam_test::highwayIni());
	ASSERT_NO_THROW(loadScenarioFromText(ini));
	// missing keys
	expectRejected(removeIniKey(ini, "Scenario", "steps"), {"[Scenario] steps", "missing"});
	expectRejected(removeIniKey(ini, "Highway", "lane_width"), {"[Highway] lane_width", "missing"});
	expectRejected(removeIniKey(ini, "Agent2", "speed"), {"[Agent2] speed", "missing"});
	expectRejected(removeIniKey(ini, "Noise", "level"), {"[Noise] level"});
	// negative counts
	expectRejected(setIniKey(ini, "Highway", "num_landmarks", "-5"),
	               {"[Highway] num_landmarks", "negative"});
	expectRejected(setIniKey(ini, "Highway", "num_agents", "-1"),
	               {"[Highway] num_agents", "negative"});
	// lane changes outside the road
	expectRejected(setIniKey(ini, "Agent1", "lane_changes", "[14 5 3]"),
	               {"[Agent1] lane_changes", "lane 3", "outside the road"});
	expectRejected(setIniKey(ini, "Agent2", "lane_changes", "[26 4 1; 40 4 -1]"),
	               {"[Agent2] lane_changes", "lane -1", "outside the road"});
	expectRejected(setIniKey(ini, "Agent1", "lane0", "5"), {"[Agent1] lane0", "outside the road"});
	expectRejected(setIniKey(ini, "Ego", "lane_changes", "[46 5 7]"),
	               {"[Ego] lane_changes", "lane 7"});
	// unknown noise level
	expectRejected(setIniKey(ini, "Noise", "level", "w4v2"), {"[Noise] level", "w4v2"});
	// other invalid values
	expectRejected(setIniKey(ini, "Agent1", "lane_changes", "[14 5]"),
	               {"[Agent1] lane_changes", "triples"});
	expectRejected(setIniKey(ini, "Agent1", "speed_changes", "[8 6 18; 10 6 15]"),
	               {"[Agent1] speed_changes", "overlaps"});
	expectRejected(setIniKey(ini, "Scenario", "dt", "0"), {"[Scenario] dt", "> 0"});
	expectRejected(setIniKey(ini, "Scenario", "world_seed", "-3"), {"[Scenario] world_seed"});
	expectRejected(setIniKey(ini, "Sensor", "range", "abc"), {"[Sensor] range", "not a number"});
	expectRejected(setIniKey(ini, "Agent3", "type", "bicycle"), {"[Agent3] type", "bicycle"});
	expectRejected(setIniKey(ini, "Agent3", "num_features", "3"), {"[Agent3] num_features"});
	expectRejected(setIniKey(ini, "Highway", "num_lanse", "3"),
	               {"[Highway] num_lanse", "unknown key"});
	expectRejected(setIniKey(ini, "Noise", "sigma_w", "[1e-4 1e-4 1e-6]"),
	               {"[Noise] sigma_w", "conflicts"});
	expectRejected(setIniKey(ini, "Highway", "num_agents", "4"), {"[Agent4] type", "missing"});
}

TEST(SimOptions, BadIniFileIsNamedInTheError)
{
	const dynslam_test::TTempDir tmp("sim_bad_scenario");  // removed at the end of the test
	const std::string path = tmp.path() + "/bad_scenario.ini";
	{
		std::ofstream f(path);
		f << setIniKey(readFile(dynslam_test::highwayIni()), "Sensor", "range", "abc");
	}
	try
	{
		loadScenario(path);
		FAIL() << "expected a rejection";
	}
	catch (const std::invalid_argument& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("scenario file '" + path + "': [Sensor] range"), std::string::npos) << m;
	}
	std::filesystem::remove(path);
}

TEST(SimOptions, CustomNoiseAndRangeBearingModel)
{
	std::string ini = readFile(dynslam_test::highwayIni());
	ini = setIniKey(ini, "Noise", "level", "custom");
	ini = setIniKey(ini, "Noise", "sigma_w", "[4e-4 1e-4 2e-6]");
	ini = setIniKey(ini, "Noise", "sigma_v", "[1e-4 0; 0 4e-4]");
	TScenarioOptions o = loadScenarioFromText(ini);
	EXPECT_EQ(o.Sigma_w(0, 0), 4e-4);
	EXPECT_EQ(o.Sigma_0, o.Sigma_w);
	EXPECT_EQ(o.Sigma_v(1, 1), 4e-4);
	expectRejected(removeIniKey(ini, "Noise", "sigma_v"), {"[Noise] sigma_v", "missing"});
	expectRejected(setIniKey(ini, "Noise", "sigma_v", "[1e-4 -1e-4]"),
	               {"[Noise] sigma_v", "positive"});

	std::string rb =
	    setIniKey(readFile(dynslam_test::highwayIni()), "Sensor", "noise_model", "range_bearing");
	expectRejected(rb, {"[Noise] std_range", "missing"});
	rb = setIniKey(rb, "Noise", "std_range", "0.05");
	rb = setIniKey(rb, "Noise", "std_yaw", "0.002");
	o = loadScenarioFromText(rb);
	EXPECT_EQ(o.noise_model, dynslam::models::MeasurementModel::RangeBearing);
	EXPECT_EQ(o.std_range, 0.05);
	EXPECT_EQ(o.std_yaw, 0.002);
}

TEST(SimOptions, GeneratedScenarioRejectsBadCounts)
{
	const std::string ini =
	    readFile(std::string(DYNSLAM_CONFIG_DIR) + "/generated_small_scenario.ini");
	ASSERT_NO_THROW(loadScenarioFromText(ini));
	expectRejected(setIniKey(ini, "Generated", "num_cars", "-2"),
	               {"[Generated] num_cars", "negative"});
	expectRejected(setIniKey(ini, "Generated", "num_landmarks", "100001"),
	               {"[Generated] num_landmarks"});
	expectRejected(setIniKey(ini, "Generated", "features_per_car", "0"),
	               {"[Generated] features_per_car"});
	expectRejected(setIniKey(ini, "Generated", "features_per_car", "1001"),
	               {"[Generated] features_per_car"});
	expectRejected(removeIniKey(ini, "Generated", "num_pedestrians"),
	               {"[Generated] num_pedestrians", "missing"});
	expectRejected(setIniKey(ini, "Generated", "track_radius", "10"), {"[Generated] track_radius"});
}
