/** The scenario families of issue 28 item 4 (config/tunnel_braking.ini,
 * tunnel_stop_and_go.ini, highway_cutins.ini, circle_road.ini, circle_road_no_landmarks.ini,
 * tunnel_accel.ini, tunnel_markov.ini): they load, regenerate from their dump, take other seeds,
 * and do what their comments say (a stop-and-go car's speed reaches 0 inside the landmark gap,
 * hard brakes inside the gap, cut-ins in front of the ego, a circle without landmarks). */
#include <dynslam/sim/TScenarioOptions.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam;

namespace
{
sim::TScenarioOptions family(const std::string& name)
{
	return sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/" + name);
}

/** Speed of an object's feature centroid between steps k - 1 and k [m/s]. */
double objectSpeed(const io::TGroundTruth& gt, size_t obj, size_t k, double dt)
{
	const auto& F = gt.objects[obj].features;
	return (F[k].rowwise().mean() - F[k - 1].rowwise().mean()).norm() / dt;
}

double egoSpeed(const io::TGroundTruth& gt, size_t k, double dt)
{
	return (gt.ego[k].head<2>() - gt.ego[k - 1].head<2>()).norm() / dt;
}
}  // namespace

TEST(SimFamilies, EveryFamilyLoadsDumpsAndTakesOtherSeeds)
{
	for (const std::string file :
	     {"tunnel_braking.ini", "tunnel_stop_and_go.ini", "tunnel_accel.ini", "tunnel_markov.ini",
	      "highway_cutins.ini", "circle_road.ini", "circle_road_no_landmarks.ini"})
	{
		SCOPED_TRACE(file);
		sim::TScenarioOptions o = family(file);
		std::ostringstream dumped;
		o.dumpToTextStream(dumped);
		const io::TGroundTruth gt = sim::buildGroundTruth(o);
		const io::TGroundTruth back =
		    sim::buildGroundTruth(sim::loadScenarioFromText(dumped.str()));
		EXPECT_EQ(back.ego, gt.ego);
		ASSERT_EQ(back.objects.size(), gt.objects.size());
		for (size_t i = 0; i < gt.objects.size(); ++i)
			EXPECT_EQ(back.objects[i].features, gt.objects[i].features);
		// Other seeds (dynslam-simulate --world-seed / --noise-seed): another world where the
		// landmarks are drawn, other readings.
		sim::TScenarioOptions other = o;
		other.world_seed = 3001;
		other.noise_seed = 3001;
		const io::TGroundTruth g2 = sim::buildGroundTruth(other);
		if (!gt.landmarks.empty())
		{
			EXPECT_NE(g2.landmarks, gt.landmarks);
		}
		const auto r1 = sim::simulateMeasurements(gt, o, o.noise_seed);
		const auto r2 = sim::simulateMeasurements(g2, other, other.noise_seed);
		const auto z1 = r1.frames[5]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		const auto z2 = r2.frames[5]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		ASSERT_FALSE(z1->sensedData.empty());
		EXPECT_NE(z1->sensedData[0].range, z2->sensedData[0].range);
	}
}

TEST(SimFamilies, StopAndGoCarsReachZeroSpeedInsideTheGap)
{
	const sim::TScenarioOptions o = family("tunnel_stop_and_go.ini");
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	// Every car and the ego: at rest (speed exactly 0 between two steps) at some step inside
	// the gap, and back at speed afterwards.
	for (size_t obj = 0; obj <= gt.objects.size(); ++obj)
	{
		SCOPED_TRACE(obj);
		const bool ego = obj == gt.objects.size();
		double vmin = 1e9, vlast = 0;
		size_t kmin = 0;
		for (size_t k = 1; k < gt.ego.size(); ++k)
		{
			const double v = ego ? egoSpeed(gt, k, o.dt) : objectSpeed(gt, obj, k, o.dt);
			if (v < vmin) vmin = v, kmin = k;
			vlast = v;
		}
		EXPECT_LT(vmin, 1e-9);
		EXPECT_TRUE(o.inLandmarkGap(gt.ego[kmin].x())) << gt.ego[kmin].x();
		EXPECT_GT(vlast, 16.0);
	}
	// The shipped tunnel without the stops never slows down below 16 m/s.
	const io::TGroundTruth steady = sim::buildGroundTruth(family("tunnel.ini"));
	for (size_t k = 1; k < steady.ego.size(); ++k) EXPECT_GT(objectSpeed(steady, 0, k, 0.5), 16.0);
}

TEST(SimFamilies, HardBrakesHappenInsideTheGap)
{
	const sim::TScenarioOptions o = family("tunnel_braking.ini");
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	for (size_t obj = 0; obj < gt.objects.size(); ++obj)
	{
		SCOPED_TRACE(obj);
		double decel = 0, vmin = 1e9;
		for (size_t k = 2; k < gt.ego.size(); ++k)
		{
			const double dv = objectSpeed(gt, obj, k - 1, o.dt) - objectSpeed(gt, obj, k, o.dt);
			if (dv / o.dt > decel && o.inLandmarkGap(gt.ego[k].x())) decel = dv / o.dt;
			vmin = std::min(vmin, objectSpeed(gt, obj, k, o.dt));
		}
		EXPECT_GT(decel, 6.0);                     // [m/s^2] averaged over one step: a hard brake
		EXPECT_LT(vmin, 6.05);                     // down to 6 m/s (Agent1) and 5 m/s (Agent2)
		EXPECT_TRUE(gt.objects[obj].visible[60]);  // still in view at t = 30 s
	}
}

TEST(SimFamilies, CutInsEndInTheEgoLaneAheadOfTheEgo)
{
	const sim::TScenarioOptions o = family("highway_cutins.ini");
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	ASSERT_EQ(o.highway.agents.size(), 3u);
	for (size_t i = 0; i < 3; ++i)
	{
		SCOPED_TRACE(i);
		const sim::TRamp& cut = o.highway.agents[i].lane_changes.front();
		EXPECT_EQ(cut.target, o.highway.ego_lane);  // into the ego's lane ...
		const size_t k0 = size_t(std::lround(cut.t_start / o.dt));
		const size_t k1 = size_t(std::ceil((cut.t_start + cut.duration) / o.dt));
		const Eigen::Vector2d c = gt.objects[i].features[k1].rowwise().mean();
		const Eigen::Vector2d c0 = gt.objects[i].features[k0].rowwise().mean();
		EXPECT_NEAR(c.y(), gt.ego[k1].y(), 1e-6);           // ... where it ends,
		EXPECT_GT(std::abs(c0.y() - gt.ego[k0].y()), 3.0);  // from a neighbouring lane,
		const double ahead = c0.x() - gt.ego[k0].x();       // in front of the ego, in view
		EXPECT_GT(ahead, 8.0);
		EXPECT_LT(ahead, 25.0);
		EXPECT_TRUE(gt.objects[i].visible[k0]);
	}
}

TEST(SimFamilies, CircularRoadWithAndWithoutLandmarks)
{
	const sim::TScenarioOptions with = family("circle_road.ini");
	const sim::TScenarioOptions without = family("circle_road_no_landmarks.ini");
	EXPECT_GT(with.generated.track_radius, 0);
	EXPECT_EQ(without.generated.track_radius, with.generated.track_radius);
	const io::TGroundTruth g1 = sim::buildGroundTruth(with), g0 = sim::buildGroundTruth(without);
	EXPECT_EQ(g1.landmarks.size(), 120u);
	EXPECT_TRUE(g0.landmarks.empty());
	// The same road and objects: only the landmarks differ (they are drawn first from the world
	// seed, so the objects' draws differ; the ego does not).
	EXPECT_EQ(g0.ego, g1.ego);
	// Without landmarks every reading is of a moving object, and there are readings.
	const auto run = sim::simulateMeasurements(g0, without, without.noise_seed);
	size_t readings = 0;
	for (const auto& f : run.frames)
		for (const auto& z :
		     f->getObservationByClass<mrpt::obs::CObservationBearingRange>()->sensedData)
		{
			EXPECT_GE(z.landmarkID, 100000);
			++readings;
		}
	EXPECT_GT(readings, 1000u);
}
