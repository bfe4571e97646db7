#pragma once
/** @file TScenarioOptions.h
 * Everything that defines a simulated scenario, read from an INI file (config/highway.ini,
 * config/generated_*.ini). Strict: required keys throw, invalid or unknown keys are rejected
 * with a message naming [section] key = value. Every parameter is listed with its value in
 * doc/simulator.md.
 *
 * Sections: [Scenario] [Sensor] [Noise], then either [Highway] [Ego] [Agent1]..[AgentN]
 * (type = highway) or [Generated] (type = generated). */
#include <dynslam/models/measurement.h>
#include <dynslam/sim/motion.h>
#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::sim
{
enum class ScenarioType
{
	Highway,
	Generated
};

/** Sigma_w (3x3, odometry increment) and Sigma_v (2x2, Cartesian measurement) of a level. */
struct TNoiseLevel
{
	Eigen::Matrix3d Sigma_w = Eigen::Matrix3d::Zero();
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Zero();
};
/** The grid of eq. (5)-(7): "w1v1".."w3v3", plus "none" (noise-free). Case-insensitive.
 * Throws std::invalid_argument naming the unknown level. */
TNoiseLevel noiseLevel(const std::string& name);

/** One moving agent of the highway ([AgentN] section). */
struct THighwayAgent
{
	std::string section;  ///< "Agent1", ...
	enum class Kind
	{
		Car,
		Pedestrian
	} kind = Kind::Car;
	double x0 = 0;                     ///< start position along the road [m]
	int lane0 = 0;                     ///< car: start lane (0 = rightmost)
	double y0 = 0;                     ///< pedestrian: start lateral position [m]
	double speed = 0;                  ///< initial speed along the road [m/s]
	std::vector<TRamp> speed_changes;  ///< (t_start, duration, new speed)
	std::vector<TRamp> lane_changes;   ///< car: (t_start, duration, target lane)
	std::vector<TRamp> lateral_moves;  ///< pedestrian: (t_start, duration, target y [m])
	double length = 4.5, width = 1.8;  ///< car body [m]; pedestrian: width = shoulder width
	int num_features = 4;              ///< car: 4 (corners); pedestrian: 1 or 2
};

struct THighwayOptions
{
	double length = 1000;  ///< road length [m]
	int num_lanes = 3;
	double lane_width = 3.5;
	int ego_lane = 1;  ///< the ego's start lane; its centre is y = 0
	int num_landmarks = 40;
	double landmark_offset_min = 3, landmark_offset_max = 30;  ///< from the road edge [m]
	THighwayAgent ego;                  ///< [Ego]: kind Car, lane0 = ego_lane, x0 = 0
	std::vector<THighwayAgent> agents;  ///< [Agent1]..[AgentN]

	/** Lateral position of a lane centre (ego lane at 0). */
	double laneY(int lane) const { return (lane - ego_lane) * lane_width; }
	double roadLeft() const { return (num_lanes - ego_lane - 0.5) * lane_width; }
	double roadRight() const { return -(ego_lane + 0.5) * lane_width; }
};

struct TGeneratedOptions
{
	double track_radius = 0;  ///< 0: straight track along x; > 0: circle through the origin
	double ego_speed = 10;    ///< [m/s]
	int num_landmarks = 200;
	double landmark_offset_min = 3, landmark_offset_max = 30;  ///< from the track centre [m]
	int num_lanes = 3;  ///< lanes for the cars (ego lane in the middle), width lane_width
	double lane_width = 3.5;
	int num_cars = 2, num_pedestrians = 1, num_rotating = 1;
	int features_per_car = 4, features_per_pedestrian = 2, features_per_rotating = 3;
	double car_length = 4.5, car_width = 1.8, pedestrian_width = 0.5, rotating_radius = 1.0;
	double car_speed_factor_min = 0.8, car_speed_factor_max = 1.2;  ///< times ego_speed
	double pedestrian_speed = 1.4;                                  ///< crossing speed [m/s]
	double yaw_rate_max = 0.5;  ///< rotating objects: |yaw rate| uniform in [0.1, max] [rad/s]
	double object_spread = 60;  ///< objects start within this distance of the ego [m]
};

struct TScenarioOptions : public mrpt::config::CLoadableOptions
{
	// [Scenario]
	ScenarioType type = ScenarioType::Highway;
	std::string name = "highway";  ///< base name of the output files
	double dt = 0.5;               ///< [s]
	int steps = 120;               ///< the scenario has steps + 1 poses, k = 0..steps
	uint32_t world_seed = 1;       ///< landmark placement, generated objects
	uint32_t noise_seed = 1;       ///< odometry and measurement noise
	double start_time = 1.6e9;     ///< timestamp of step 0 [s since 1970]; t_k = start + k dt

	// [Sensor]
	double sensor_range = 55;  ///< [m]; static landmarks by true range, objects by centroid
	std::string sensor_label = "RB";
	models::MeasurementModel noise_model = models::MeasurementModel::Cartesian;
	double typical_range = 27.5;  ///< for the equivalent yaw std (default: sensor_range / 2)
	/** The sensor's pose on the robot (x [m], y [m], yaw [rad]), written to every observation's
	 * sensorLocationOnRobot; readings are taken from x (+) sensor_pose. */
	Eigen::Vector3d sensor_pose = Eigen::Vector3d::Zero();

	// [Noise]
	std::string noise_level = "w2v2";  ///< w1v1..w3v3, none, or custom
	Eigen::Matrix3d Sigma_w = Eigen::Matrix3d::Zero();
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Zero();  ///< Cartesian model
	Eigen::Matrix3d Sigma_0 = Eigen::Matrix3d::Zero();  ///< = Sigma_w (filter prior)
	double std_range = 0, std_yaw = 0;  ///< range_bearing model: the noise; cartesian: equivalent

	THighwayOptions highway;
	TGeneratedOptions generated;

	/** Reads the whole scenario; `section` is unused (the scenario spans several sections). */
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
	                        const std::string& section = "") override;
	/** Writes a complete INI that loadFromConfigFile() reads back to the same options (the
	 * effective configuration, <base>_scenario.ini), including the derived values. */
	void dumpToTextStream(std::ostream& out) const override;

	/** Sets level (w1v1..w3v3 | none): Sigma_w, Sigma_v, Sigma_0 and the equivalent stds. */
	void setNoiseLevel(const std::string& level);
	/** Recomputes the derived stds from Sigma_v (cartesian model). */
	void updateEquivalentStds();
	/** Cross-field checks (throws std::invalid_argument naming the key). */
	void validate() const;
	size_t numSteps() const { return size_t(steps) + 1; }
	double stepTime(size_t k) const { return double(k) * dt; }
};

/** Loads a scenario INI file (throws with the file name on a missing file). */
TScenarioOptions loadScenario(const std::string& iniPath);
/** Same, from INI text. */
TScenarioOptions loadScenarioFromText(const std::string& iniText);
}  // namespace dynslam::sim
