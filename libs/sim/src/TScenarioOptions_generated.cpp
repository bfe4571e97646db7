/** @file TScenarioOptions_generated.cpp
 * The [Generated] section of TScenarioOptions: strict reading and the effective-configuration
 * writer. */
#include <dynslam/common/config_utils.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <utility>

#include "options_format.h"
#include "options_sections.h"

namespace dynslam::sim::detail
{
namespace cfg = dynslam::config;
using mrpt::config::CConfigFileBase;

/** Reads [Generated] into g (defaults kept for absent optional keys). */
void readGenerated(const CConfigFileBase& c, TGeneratedOptions& g)
{
	const std::string G = "Generated";
	cfg::rejectUnknownKeys(c, G,
	                       {"track_radius",
	                        "ego_speed",
	                        "num_landmarks",
	                        "landmark_offset_min",
	                        "landmark_offset_max",
	                        "num_lanes",
	                        "lane_width",
	                        "num_cars",
	                        "num_pedestrians",
	                        "num_rotating",
	                        "features_per_car",
	                        "features_per_pedestrian",
	                        "features_per_rotating",
	                        "car_length",
	                        "car_width",
	                        "pedestrian_width",
	                        "rotating_radius",
	                        "car_speed_factor_min",
	                        "car_speed_factor_max",
	                        "pedestrian_speed",
	                        "yaw_rate_max",
	                        "object_spread",
	                        "car_brakes",
	                        "car_brake_decel",
	                        "car_brake_speed_factor"});
	g.track_radius = cfg::readNonNegative(c, G, "track_radius", 0, true);
	g.ego_speed = cfg::readPositive(c, G, "ego_speed", 10, true);
	g.num_landmarks = int(readCount(c, G, "num_landmarks", 200, true, ids::kStaticMax + 1));
	g.landmark_offset_min = cfg::readNonNegative(c, G, "landmark_offset_min", 3);
	g.landmark_offset_max = cfg::readPositive(c, G, "landmark_offset_max", 30);
	if (g.landmark_offset_max < g.landmark_offset_min)
		cfg::fail(G, "landmark_offset_max", fmt(g.landmark_offset_max),
		          "smaller than landmark_offset_min");
	g.num_lanes = int(readCount(c, G, "num_lanes", 3, false, 100));
	if (g.num_lanes < 1) cfg::fail(G, "num_lanes", "0", "need at least one lane");
	g.lane_width = cfg::readPositive(c, G, "lane_width", 3.5);
	const long maxObj = ids::kMaxObject + 1;
	g.num_cars = int(readCount(c, G, "num_cars", 2, true, maxObj));
	g.num_pedestrians = int(readCount(c, G, "num_pedestrians", 1, true, maxObj));
	g.num_rotating = int(readCount(c, G, "num_rotating", 1, true, maxObj));
	if (long(g.num_cars) + g.num_pedestrians + g.num_rotating > maxObj)
		cfg::fail(G, "num_cars", std::to_string(g.num_cars), "too many objects in total");
	const long maxF = ids::kFeaturesPerObject;
	g.features_per_car = int(readCount(c, G, "features_per_car", 4, false, maxF));
	g.features_per_pedestrian = int(readCount(c, G, "features_per_pedestrian", 2, false, maxF));
	g.features_per_rotating = int(readCount(c, G, "features_per_rotating", 3, false, maxF));
	for (const auto& [k, v] : {std::pair<const char*, int>{"features_per_car", g.features_per_car},
	                           {"features_per_pedestrian", g.features_per_pedestrian},
	                           {"features_per_rotating", g.features_per_rotating}})
		if (v < 1) cfg::fail(G, k, std::to_string(v), "an object needs at least one feature");
	g.car_length = cfg::readPositive(c, G, "car_length", 4.5);
	g.car_width = cfg::readPositive(c, G, "car_width", 1.8);
	g.pedestrian_width = cfg::readPositive(c, G, "pedestrian_width", 0.5);
	g.rotating_radius = cfg::readPositive(c, G, "rotating_radius", 1.0);
	g.car_speed_factor_min = cfg::readNonNegative(c, G, "car_speed_factor_min", 0.8);
	g.car_speed_factor_max = cfg::readNonNegative(c, G, "car_speed_factor_max", 1.2);
	if (g.car_speed_factor_max < g.car_speed_factor_min)
		cfg::fail(G, "car_speed_factor_max", fmt(g.car_speed_factor_max),
		          "smaller than car_speed_factor_min");
	g.pedestrian_speed = cfg::readPositive(c, G, "pedestrian_speed", 1.4);
	g.yaw_rate_max = cfg::readPositive(c, G, "yaw_rate_max", 0.5);
	g.object_spread = cfg::readPositive(c, G, "object_spread", 60);
	g.car_brakes = int(readCount(c, G, "car_brakes", 0, false, 1000));
	g.car_brake_decel = cfg::readPositive(c, G, "car_brake_decel", 6.0);
	g.car_brake_speed_factor = cfg::readNonNegative(c, G, "car_brake_speed_factor", 0.2);
	if (g.car_brake_speed_factor >= 1)
		cfg::fail(G, "car_brake_speed_factor", fmt(g.car_brake_speed_factor),
		          "a brake slows down: must be < 1");
	if (g.track_radius > 0)
	{
		const double reach = std::max(g.landmark_offset_max,
		                              (g.num_lanes + 1.0) * g.lane_width + g.rotating_radius + 2.0);
		if (reach >= g.track_radius)
			cfg::fail(G, "track_radius", fmt(g.track_radius),
			          "must exceed the lateral extent of the world (" + fmt(reach) + " m)");
	}
}

void dumpGenerated(std::ostream& o, const TGeneratedOptions& g)
{
	o << "\n[Generated]\n";
	o << "track_radius = " << fmt(g.track_radius) << "\n";
	o << "ego_speed = " << fmt(g.ego_speed) << "\n";
	o << "num_landmarks = " << g.num_landmarks << "\n";
	o << "landmark_offset_min = " << fmt(g.landmark_offset_min) << "\n";
	o << "landmark_offset_max = " << fmt(g.landmark_offset_max) << "\n";
	o << "num_lanes = " << g.num_lanes << "\n";
	o << "lane_width = " << fmt(g.lane_width) << "\n";
	o << "num_cars = " << g.num_cars << "\n";
	o << "num_pedestrians = " << g.num_pedestrians << "\n";
	o << "num_rotating = " << g.num_rotating << "\n";
	o << "features_per_car = " << g.features_per_car << "\n";
	o << "features_per_pedestrian = " << g.features_per_pedestrian << "\n";
	o << "features_per_rotating = " << g.features_per_rotating << "\n";
	o << "car_length = " << fmt(g.car_length) << "\n";
	o << "car_width = " << fmt(g.car_width) << "\n";
	o << "pedestrian_width = " << fmt(g.pedestrian_width) << "\n";
	o << "rotating_radius = " << fmt(g.rotating_radius) << "\n";
	o << "car_speed_factor_min = " << fmt(g.car_speed_factor_min) << "\n";
	o << "car_speed_factor_max = " << fmt(g.car_speed_factor_max) << "\n";
	o << "pedestrian_speed = " << fmt(g.pedestrian_speed) << "\n";
	o << "yaw_rate_max = " << fmt(g.yaw_rate_max) << "\n";
	o << "object_spread = " << fmt(g.object_spread) << "\n";
	if (g.car_brakes > 0)  // written only when on: the other effective configurations unchanged
	{
		o << "car_brakes = " << g.car_brakes << "\n";
		o << "car_brake_decel = " << fmt(g.car_brake_decel) << "\n";
		o << "car_brake_speed_factor = " << fmt(g.car_brake_speed_factor) << "\n";
	}
}
}  // namespace dynslam::sim::detail
