/** The simulator's odometry bias (issue 17; [Noise] odometry_rate_bias_deg_s,
 * odometry_scale_error): the reading is (dx / (1 - s), dy / (1 - s), dtheta + b_w dt) of the
 * true increment plus the same noise draws as without the bias; keys dumped and reloaded, bad
 * values rejected naming the key. */
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CActionRobotMovement2D.h>

#include <cmath>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam;

namespace
{
std::string highwayWith(const std::string& keys)
{
	std::string ini = dynslam_test::readFile(std::string(DYNSLAM_CONFIG_DIR) + "/highway.ini");
	const size_t at = ini.find("[Noise]\n");
	EXPECT_NE(at, std::string::npos);
	return ini.insert(at + 8, keys);
}

Eigen::Vector3d increment(const mrpt::obs::CActionCollection::Ptr& a)
{
	const auto p = a->getBestMovementEstimation()->poseChange->getMeanVal();
	return {p.x(), p.y(), p.phi()};
}
}  // namespace

TEST(SimOdometryBias, ReadingIsTheBiasedTrueIncrementPlusTheSameNoise)
{
	sim::TScenarioOptions clean = sim::loadScenarioFromText(highwayWith(""));
	sim::TScenarioOptions biased = sim::loadScenarioFromText(
	    highwayWith("odometry_rate_bias_deg_s = 1\nodometry_scale_error = 0.05\n"));
	clean.steps = biased.steps = 40;
	EXPECT_DOUBLE_EQ(biased.odometry_rate_bias, M_PI / 180);
	EXPECT_DOUBLE_EQ(biased.odometry_scale_error, 0.05);
	const io::TGroundTruth gt = sim::buildGroundTruth(clean);
	const io::TGroundTruth gtb = sim::buildGroundTruth(biased);
	ASSERT_EQ(gt.ego.size(), gtb.ego.size());
	for (size_t k = 0; k < gt.ego.size(); ++k) EXPECT_EQ(gt.ego[k], gtb.ego[k]);  // unchanged
	const auto rc = sim::simulateMeasurements(gt, clean, 3);
	const auto rb = sim::simulateMeasurements(gt, biased, 3);
	const double dt = clean.dt, s = 0.05;
	EXPECT_EQ(increment(rb.actions[0]), Eigen::Vector3d::Zero());
	for (size_t k = 1; k < gt.ego.size(); ++k)
	{
		const Eigen::Vector3d uc = increment(rc.actions[k]), ub = increment(rb.actions[k]);
		const Eigen::Vector3d ut = models::poseDifference(gt.ego[k], gt.ego[k - 1]);
		// same noise: ub - ut_biased == uc - ut
		EXPECT_NEAR(ub[0] - ut[0] / (1 - s), uc[0] - ut[0], 1e-12) << k;
		EXPECT_NEAR(ub[1] - ut[1] / (1 - s), uc[1] - ut[1], 1e-12) << k;
		EXPECT_NEAR(models::wrapToPi(ub[2] - uc[2]), M_PI / 180 * dt, 1e-12) << k;
	}
	// measurements unchanged
	ASSERT_EQ(rc.frames.size(), rb.frames.size());
}

TEST(SimOdometryBias, KeysDumpedReloadedAndChecked)
{
	const sim::TScenarioOptions o = sim::loadScenarioFromText(
	    highwayWith("odometry_rate_bias_deg_s = -0.5\nodometry_scale_error = 0.02\n"));
	std::ostringstream a, b;
	o.dumpToTextStream(a);
	EXPECT_NE(a.str().find("odometry_rate_bias_deg_s = -0.5"), std::string::npos);
	const sim::TScenarioOptions o2 = sim::loadScenarioFromText(a.str());
	o2.dumpToTextStream(b);
	EXPECT_EQ(a.str(), b.str());
	EXPECT_DOUBLE_EQ(o2.odometry_rate_bias, o.odometry_rate_bias);
	// zero bias: the keys are not written (the shipped <base>_scenario.ini files stay as they are)
	std::ostringstream c;
	sim::loadScenarioFromText(highwayWith("")).dumpToTextStream(c);
	EXPECT_EQ(c.str().find("odometry_"), std::string::npos);
	for (const std::string bad : {"odometry_scale_error = 1\n", "odometry_rate_bias_deg_s = nan\n",
	                              "odometry_rate_bias_deg_s = fast\n"})
		EXPECT_THROW(sim::loadScenarioFromText(highwayWith(bad)), std::invalid_argument) << bad;
	try
	{
		sim::loadScenarioFromText(highwayWith("odometry_scale_error = -1.5\n"));
		ADD_FAILURE() << "accepted";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("odometry_scale_error"), std::string::npos);
	}
}
