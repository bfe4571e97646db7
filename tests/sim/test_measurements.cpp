/** Simulated odometry and measurements: noise-free runs reproduce h(ground truth), noisy runs
 * have the configured covariances (chi-square), identical seeds give identical data. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/LU>
#include <set>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam::sim;
using mrpt::obs::CActionRobotMovement2D;
using mrpt::obs::CObservationBearingRange;

namespace
{
Eigen::Vector3d increment(const TSimulatedRun& run, size_t k, Eigen::Matrix3d* cov = nullptr)
{
	const auto a = run.actions[k]->getActionByClass<CActionRobotMovement2D>();
	EXPECT_TRUE(a);
	const auto g =
	    std::dynamic_pointer_cast<mrpt::poses::CPosePDFGaussian>(a->poseChange.get_ptr());
	EXPECT_TRUE(g);
	// not emOdometry: MRPT would rebuild the covariance from its own motion model on reading
	EXPECT_EQ(a->estimationMethod, CActionRobotMovement2D::emScan2DMatching);
	EXPECT_EQ(a->rawOdometryIncrementReading, g->mean);
	if (cov) *cov = g->cov.asEigen();
	return {g->mean.x(), g->mean.y(), g->mean.phi()};
}

CObservationBearingRange::Ptr observation(const TSimulatedRun& run, size_t k)
{
	auto o = run.frames[k]->getObservationByClass<CObservationBearingRange>();
	EXPECT_TRUE(o);
	return o;
}

/** True position of the landmark or object feature with this ID at step k. */
Eigen::Vector2d truePosition(const dynslam::io::TGroundTruth& gt, size_t k, int32_t id)
{
	if (dynslam::ids::isStatic(id)) return gt.landmarks.at(id);
	return gt.objects.at(dynslam::ids::objectOf(id)).features[k].col(dynslam::ids::featureOf(id));
}

struct TChi2
{
	double sum = 0;
	size_t n = 0;  // samples
	int dim = 0;
	void add(double nees) { sum += nees, ++n; }
	/** Is sum ~ chi2(n * dim) inside the 99.9% interval? */
	bool inside(double* lo = nullptr, double* hi = nullptr) const
	{
		const auto [a, b] = dynslam_test::chi2Interval(double(n) * dim);
		if (lo) *lo = a;
		if (hi) *hi = b;
		return sum >= a && sum <= b;
	}
};
}  // namespace

TEST(SimMeasurements, NoiseFreeRunReproducesTheModel)
{
	TScenarioOptions o = dynslam_test::highwayOptions();
	o.setNoiseLevel("none");
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const TSimulatedRun run = simulateMeasurements(gt, o, 1);
	ASSERT_EQ(run.actions.size(), gt.numSteps());
	ASSERT_EQ(run.frames.size(), gt.numSteps());
	Eigen::Matrix3d cov;
	EXPECT_EQ(increment(run, 0, &cov), Eigen::Vector3d::Zero());  // ACT_0: zero increment
	EXPECT_EQ(cov, Eigen::Matrix3d::Zero());
	double maxOdo = 0, maxRel = 0;
	size_t count = 0;
	for (size_t k = 1; k < gt.numSteps(); ++k)
	{
		const Eigen::Vector3d u = increment(run, k);
		const Eigen::Vector3d uTrue = dynslam::models::poseDifference(gt.ego[k], gt.ego[k - 1]);
		maxOdo = std::max(maxOdo, (u - uTrue).cwiseAbs().maxCoeff());
		// composing the increments gives the true path
		EXPECT_LT((dynslam::models::composePose(gt.ego[k - 1], u) - gt.ego[k]).norm(), 1e-12);
	}
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		const auto obs = observation(run, k);
		for (const auto& m : obs->sensedData)
		{
			const Eigen::Vector2d h =
			    dynslam::models::cartesianObserve(gt.ego[k], truePosition(gt, k, m.landmarkID));
			const Eigen::Vector2d z =
			    dynslam::models::rangeBearingToCartesian(Eigen::Vector2d(m.range, m.yaw));
			// float storage: 0.5 ulp relative on range and yaw
			maxRel = std::max(maxRel, (z - h).norm() / h.norm());
			EXPECT_LT((z - h).norm(), 3e-7 * h.norm() + 1e-12)
			    << "k " << k << " id " << m.landmarkID;
			++count;
		}
	}
	EXPECT_LT(maxOdo, 1e-13);
	EXPECT_GT(count, 1000u);
	std::cout << "[          ] noise-free: " << count << " readings, max |z - h| / |h| = " << maxRel
	          << ", max odometry error " << maxOdo << "\n";
}

TEST(SimMeasurements, ObservationContents)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const TSimulatedRun run = simulateMeasurements(gt, o, o.noise_seed);
	std::set<int32_t> everSeen;
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		const auto obs = observation(run, k);
		EXPECT_EQ(run.frames[k]->size(), 1u);
		EXPECT_EQ(obs->sensorLabel, "RB");
		EXPECT_FLOAT_EQ(obs->maxSensorDistance, float(o.sensor_range));
		EXPECT_EQ(obs->minSensorDistance, 0);
		EXPECT_FLOAT_EQ(obs->fieldOfView_yaw, float(2 * M_PI));
		EXPECT_FALSE(obs->validCovariances);
		EXPECT_FLOAT_EQ(obs->sensor_std_range, float(o.std_range));
		EXPECT_FLOAT_EQ(obs->sensor_std_yaw, float(o.std_yaw));
		EXPECT_NEAR(mrpt::Clock::toDouble(obs->timestamp), o.start_time + 0.5 * k, 1e-6);
		// The expected set: landmarks within the true range, all features of visible objects.
		std::set<int32_t> expected, got;
		for (const auto& [id, p] : gt.landmarks)
			if ((p - gt.ego[k].head<2>()).norm() <= o.sensor_range) expected.insert(id);
		for (const auto& og : gt.objects)
			if (og.visible[k])
				for (int j = 0; j < og.num_features; ++j)
					expected.insert(dynslam::ids::objectFeatureId(og.object, j));
		for (const auto& m : obs->sensedData)
		{
			EXPECT_TRUE(got.insert(m.landmarkID).second) << "duplicate ID " << m.landmarkID;
			EXPECT_EQ(m.pitch, 0);
			everSeen.insert(m.landmarkID);
		}
		EXPECT_EQ(got, expected) << "k " << k;
	}
	// Landmarks enter and leave view: most are seen at some time, none all the time.
	EXPECT_GT(everSeen.size(), gt.landmarks.size() * 9 / 10);
}

TEST(SimMeasurements, NoiseCovariancesMatchChiSquare)
{
	TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const int runs = 25;
	uint64_t seed = 1000;  // independent seeds for every level and run
	for (const std::string level : {"w1v1", "w2v2", "w3v3", "w1v3"})
	{
		SCOPED_TRACE(level);
		o.setNoiseLevel(level);
		TChi2 odo{0, 0, 3}, meas{0, 0, 2};
		TChi2 odoComp[3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, measComp[2] = {{0, 0, 1}, {0, 0, 1}};
		const Eigen::Matrix3d Wi = o.Sigma_w.inverse();
		const Eigen::Matrix2d Vi = o.Sigma_v.inverse();
		for (int r = 0; r < runs; ++r)
		{
			const TSimulatedRun run = simulateMeasurements(gt, o, seed++);
			for (size_t k = 1; k < gt.numSteps(); ++k)
			{
				Eigen::Matrix3d cov;
				Eigen::Vector3d e = increment(run, k, &cov) -
				                    dynslam::models::poseDifference(gt.ego[k], gt.ego[k - 1]);
				e[2] = dynslam::models::wrapToPi(e[2]);
				EXPECT_EQ(cov, o.Sigma_w);
				odo.add(e.dot(Wi * e));
				for (int c = 0; c < 3; ++c) odoComp[c].add(e[c] * e[c] / o.Sigma_w(c, c));
			}
			for (size_t k = 0; k < gt.numSteps(); ++k)
				for (const auto& m : observation(run, k)->sensedData)
				{
					const Eigen::Vector2d e =
					    dynslam::models::rangeBearingToCartesian(Eigen::Vector2d(m.range, m.yaw)) -
					    dynslam::models::cartesianObserve(gt.ego[k],
					                                      truePosition(gt, k, m.landmarkID));
					meas.add(e.dot(Vi * e));
					for (int c = 0; c < 2; ++c) measComp[c].add(e[c] * e[c] / o.Sigma_v(c, c));
				}
		}
		double lo, hi;
		EXPECT_TRUE(odo.inside(&lo, &hi))
		    << "odometry NEES sum " << odo.sum << " not in [" << lo << ", " << hi << "]";
		std::cout << "[          ] " << level << " odometry: " << odo.n << " samples, mean NEES "
		          << odo.sum / odo.n << " (dof 3; 99.9% bounds of the mean [" << lo / odo.n << ", "
		          << hi / odo.n << "])\n";
		EXPECT_TRUE(meas.inside(&lo, &hi))
		    << "measurement NEES sum " << meas.sum << " not in [" << lo << ", " << hi << "]";
		std::cout << "[          ] " << level << " Cartesian measurement: " << meas.n
		          << " samples, mean NEES " << meas.sum / meas.n
		          << " (dof 2; 99.9% bounds of the mean [" << lo / meas.n << ", " << hi / meas.n
		          << "])\n";
		for (int c = 0; c < 3; ++c) EXPECT_TRUE(odoComp[c].inside()) << "odometry component " << c;
		for (int c = 0; c < 2; ++c)
			EXPECT_TRUE(measComp[c].inside()) << "measurement component " << c;
	}
}

TEST(SimMeasurements, RangeBearingNoiseModel)
{
	std::string ini = dynslam_test::readFile(dynslam_test::highwayIni());
	ini = dynslam_test::setIniKey(ini, "Sensor", "noise_model", "range_bearing");
	ini = dynslam_test::setIniKey(ini, "Noise", "std_range", "0.05");
	ini = dynslam_test::setIniKey(ini, "Noise", "std_yaw", "0.002");
	const TScenarioOptions o = loadScenarioFromText(ini);
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	TChi2 rng{0, 0, 1}, yaw{0, 0, 1};
	for (int r = 0; r < 5; ++r)
	{
		const TSimulatedRun run = simulateMeasurements(gt, o, 50 + r);
		for (size_t k = 0; k < gt.numSteps(); ++k)
			for (const auto& m : observation(run, k)->sensedData)
			{
				const Eigen::Vector2d h = dynslam::models::rangeBearingObserve(
				    gt.ego[k], truePosition(gt, k, m.landmarkID));
				rng.add(std::pow((m.range - h[0]) / o.std_range, 2));
				yaw.add(std::pow(dynslam::models::wrapToPi(m.yaw - h[1]) / o.std_yaw, 2));
			}
	}
	EXPECT_TRUE(rng.inside()) << rng.sum / rng.n;
	EXPECT_TRUE(yaw.inside()) << yaw.sum / yaw.n;
	std::cout << "[          ] range-bearing model: " << rng.n
	          << " samples, mean normalized squared range error " << rng.sum / rng.n << ", yaw "
	          << yaw.sum / yaw.n << "\n";
}

TEST(SimMeasurements, SameSeedsSameData)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const TSimulatedRun a = simulateMeasurements(gt, o, 9), b = simulateMeasurements(gt, o, 9);
	const TSimulatedRun c = simulateMeasurements(gt, o, 10), z = simulateMeasurements(gt, o, 0);
	bool anyDiff = false;
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		EXPECT_EQ(increment(a, k), increment(b, k));
		const auto oa = observation(a, k), ob = observation(b, k), oc = observation(c, k);
		ASSERT_EQ(oa->sensedData.size(), ob->sensedData.size());
		for (size_t i = 0; i < oa->sensedData.size(); ++i)
		{
			EXPECT_EQ(oa->sensedData[i].range, ob->sensedData[i].range);
			EXPECT_EQ(oa->sensedData[i].yaw, ob->sensedData[i].yaw);
			anyDiff |= oa->sensedData[i].range != oc->sensedData[i].range;
		}
	}
	EXPECT_TRUE(anyDiff);  // a different noise seed gives different noise
	EXPECT_NE(increment(z, 5), increment(a, 5));
	// Seed 0 is an ordinary seed (not time-seeded): the same data every time.
	const TSimulatedRun z2 = simulateMeasurements(gt, o, 0);
	for (size_t k = 0; k < gt.numSteps(); ++k) EXPECT_EQ(increment(z, k), increment(z2, k));
	EXPECT_THROW(simulateMeasurements(gt, o, uint64_t(1) << 32), std::invalid_argument);
}

TEST(SimMeasurements, SensorNotAtTheRobotsOrigin)
{
	// [Sensor] sensor_pose = x y yaw: every observation carries it in sensorLocationOnRobot and
	// the noise-free readings are h(x (+) s, f); the INI key round-trips; a bad value is
	// rejected naming the key.
	TScenarioOptions o = dynslam_test::highwayOptions();
	o.setNoiseLevel("none");
	o.steps = 20;
	o.sensor_pose = Eigen::Vector3d(0.3, -0.1, 0.2);
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const TSimulatedRun run = simulateMeasurements(gt, o, 1);
	size_t count = 0;
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		const auto obs = observation(run, k);
		const auto& p = obs->sensorLocationOnRobot;
		EXPECT_EQ(Eigen::Vector3d(p.x(), p.y(), p.z()), Eigen::Vector3d(0.3, -0.1, 0));
		EXPECT_NEAR(p.yaw(), 0.2, 1e-15);
		EXPECT_NEAR(p.pitch(), 0, 1e-15);
		EXPECT_NEAR(p.roll(), 0, 1e-15);
		for (const auto& m : obs->sensedData)
		{
			const Eigen::Vector2d f = truePosition(gt, k, m.landmarkID);
			const Eigen::Vector2d h =
			    dynslam::models::cartesianObserveFromSensor(gt.ego[k], o.sensor_pose, f);
			const Eigen::Vector2d z =
			    dynslam::models::rangeBearingToCartesian(Eigen::Vector2d(m.range, m.yaw));
			EXPECT_LT((z - h).norm(), 3e-7 * h.norm() + 1e-12)
			    << "k " << k << " id " << m.landmarkID;
			++count;
		}
	}
	EXPECT_GT(count, 100u);
	std::ostringstream a;
	o.dumpToTextStream(a);
	EXPECT_EQ(loadScenarioFromText(a.str()).sensor_pose, o.sensor_pose) << a.str();
	std::string bad = a.str();
	const size_t at = bad.find("sensor_pose = ");
	bad.replace(at, bad.find('\n', at) - at, "sensor_pose = 0.3 nan 0.2");
	try
	{
		loadScenarioFromText(bad);
		ADD_FAILURE() << "no exception";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("[Sensor] sensor_pose"), std::string::npos)
		    << e.what();
	}
}
