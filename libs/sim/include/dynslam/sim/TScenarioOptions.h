#pragma once
/** @file TScenarioOptions.h
 * Everything that defines a simulated scenario, read from an INI file (config/highway.ini,
 * config/generated_*.ini). Strict: required keys throw, invalid or unknown keys are rejected
 * with a message naming [section] key = value. Every parameter is listed with its value in
 * doc/simulator.md.
 *
 * Sections: [Scenario] [Sensor] [Noise], then either [Highway] [Ego] [Agent1]..[AgentN]
 * (type = highway) or [Generated] (type = generated). */
#include <dynslam/core/models/measurement.h>
#include <dynslam/sim/motion.h>
#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
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
	// Issue 12: parked / stopping agents (NaN: not set). Parked until start_moving_at_s, then
	// the speed ramps from 0 to `speed` during [start, start + start_stop_duration_s]; the
	// speed ramps to 0 during [stop - start_stop_duration_s, stop] and the agent rests from
	// stop_at_s on. True class (B_gt_classes.csv): moving iff start < t < stop.
	double start_moving_at_s = std::numeric_limits<double>::quiet_NaN();  ///< [s]
	double stop_at_s = std::numeric_limits<double>::quiet_NaN();          ///< [s]
	double start_stop_duration_s = 4;                                     ///< [s]
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
	/** Hard brakes of the cars (issue 13): each car brakes car_brakes times (0: never, the
	 * default; the world is then the one without these keys), at a random time in each of
	 * car_brakes equal slots of the run, to car_brake_speed_factor times its base speed with a
	 * peak deceleration car_brake_decel [m/s^2], holds that speed for 2 s, and speeds up
	 * again at the same rate. Drawn from a private generator: the other draws are unchanged. */
	int car_brakes = 0;
	double car_brake_decel = 6.0;
	double car_brake_speed_factor = 0.2;
};

/** [Effects] (issue 12): what a real front-end does to the readings. All off by default (the
 * output is then identical to a run without the section). Drawn from a private generator
 * seeded with (noise_seed + 0x9E3779B9) mod 2^32, so the noise draws never change. See
 * doc/simulator.md, section "Front-end effects". */
struct TReadingEffects
{
	bool anonymous_ids = false;  ///< every ID replaced by a random permutation of 0..N-1
	double missed_detection_probability = 0;  ///< per reading, independent
	int clutter_per_step = 0;                 ///< false readings per step, uniform in the disc
	bool clutter_unknown_ids = false;         ///< clutter_ids = unknown (-1) | fresh (default)
	int track_break_gap = 0;  ///< a track unseen for >= this many steps gets a new ID (0: off)
	double track_break_probability = 0;  ///< per reading of a seen track: a new ID from now on
	/** Per true reading: the ID written is -1 (MRPT's "association unknown"; the track keeps
	 * its ID for its other readings). */
	double unknown_id_probability = 0;
	/** detection_groups: each step also writes a DETECTION_GROUPS comment
	 * (dynslam/common/detection_groups.h) giving every reading of an object (moving or parked) its
	 * object index as a box ID (a detector's box that survives track breaks); static landmarks
	 * and clutter get none. Off: the rawlog is unchanged. Not a reading effect (no draws). */
	bool detection_groups = false;
	bool any() const
	{
		return anonymous_ids || missed_detection_probability > 0 || clutter_per_step > 0 ||
		       track_break_gap > 0 || track_break_probability > 0 || unknown_id_probability > 0;
	}
};

/** [ObjectMotion] (issue 28 item 4): the objects' true motion. `model = deterministic` (the
 * default, and the section may be absent): the scripted closed-form trajectories. `model =
 * markov`: the model-matched truth of the multiple-model filter (estimator::CMultipleModel):
 * every object's state s = [xi; v] (object_pose.h's pose since step 0 and its rate) starts at
 * [0; v0] (v0 the scripted motion's rate at t = 0) in initial_mode and, per step, first
 * switches mode with probability switch_prob (to each other mode with switch_prob / 3, the
 * matrix models::uniformSwitching), then moves by that mode's model with its white-acceleration
 * noise (markov_motion.h). Drawn from a private generator seeded with noise_seed. Written by
 * dumpToTextStream only when markov. */
struct TObjectMotionOptions
{
	bool markov = false;
	double switch_prob = 0;                                   ///< in [0, 1]
	Eigen::Vector3d accel_psd = Eigen::Vector3d::Zero();      ///< stationary, cv, turn modes
	Eigen::Vector3d manoeuvre_psd = Eigen::Vector3d::Zero();  ///< manoeuvre mode
	int initial_mode = 1;  ///< 0 stationary, 1 cv (default), 2 turn, 3 manoeuvre
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
	/** Stretches [start, end] in metres along the road (highway: x; generated: arc length
	 * along the track) without static landmarks (a tunnel, an open road): landmarks drawn
	 * there are removed; the draws of the others are unchanged. */
	std::vector<std::pair<double, double>> landmark_gaps;
	/** True if position s along the road lies in a landmark gap. */
	bool inLandmarkGap(double s) const
	{
		for (const auto& [a, b] : landmark_gaps)
			if (s >= a && s <= b) return true;
		return false;
	}

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
	/** A constant odometry bias (issue 17; ground truth unchanged): the reading of the true
	 * increment (dx, dy, dtheta) over dt is (dx / (1 - s), dy / (1 - s), dtheta + b_w dt)
	 * before the noise, the inverse of dynslam/core/models/odometry_bias.h. Keys
	 * odometry_rate_bias_deg_s (b_w [deg/s], default 0) and odometry_scale_error (s, in
	 * (-1, 1), default 0); written by dumpToTextStream only when non-zero. */
	double odometry_rate_bias = 0;  ///< b_w [rad/s]
	double odometry_scale_error = 0;
	/** Model-matched truth (issue 13; doc/simulator.md "Model-matched truth"; written by
	 * dumpToTextStream only when set, so the shipped datasets stay byte-identical).
	 * start_from_prior (key start_from_prior, default false): the ego's true start pose is drawn
	 * from N(0, Sigma_0), the prior a filter is given, and the whole world moves with it (the
	 * readings do not change). object_accel_psd (key object_accel_psd [q_x q_y q_theta] >= 0,
	 * default 0): every object's pose xi follows the CV model of models/object_motion.h with
	 * this white acceleration on top of its deterministic motion. Both drawn from private
	 * generators seeded from noise_seed (truth_noise.h): the noise draws never change. */
	bool start_from_prior = false;
	Eigen::Vector3d object_accel_psd = Eigen::Vector3d::Zero();

	TObjectMotionOptions object_motion;  ///< [ObjectMotion] (issue 28)

	THighwayOptions highway;
	TGeneratedOptions generated;
	TReadingEffects effects;  ///< [Effects] (issue 12)

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
	/** True class of object `obj` at time t: moving unless it is parked (before
	 * start_moving_at_s) or has stopped (from stop_at_s on). Generated objects always move. */
	bool objectMovingAt(size_t obj, double t) const;
};

/** Loads a scenario INI file (throws with the file name on a missing file). */
TScenarioOptions loadScenario(const std::string& iniPath);
/** Same, from INI text. */
TScenarioOptions loadScenarioFromText(const std::string& iniText);
}  // namespace dynslam::sim
