#pragma once
/** @file scenario.h
 * The simulator: world (ground truth) and noisy measurements, in memory, plus the rawlog and
 * ground-truth writers. See doc/simulator.md for the sensor model and the file formats.
 *
 * Step k = 0..steps, t_k = k dt. For every step the rawlog holds ACT_k (the noisy odometry
 * increment INTO pose k; ACT_0 is a zero increment with zero covariance) and SF_k (one
 * CObservationBearingRange taken at pose k). Ground truth step k is the pose of SF_k. */
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <dynslam/sim/motion.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::sim
{
/** What kind of moving object (for figures and documentation only). */
enum class ObjectKind
{
	Car,
	Pedestrian,
	Rotating
};

/** The deterministic world behind a scenario: track, ego and object motions, body-frame
 * features, static landmarks. */
struct TWorld
{
	TTrack track;
	TBodyMotion ego;
	struct TObject
	{
		ObjectKind kind = ObjectKind::Car;
		std::string name;  ///< e.g. "Agent1" or "car3"
		TBodyMotion motion;
		Eigen::Matrix2Xd body;  ///< 2 x n feature positions in the body frame
	};
	std::vector<TObject> objects;
	std::map<int32_t, Eigen::Vector2d> landmarks;
};

/** Builds the world from the options; deterministic given world_seed. */
TWorld buildWorld(const TScenarioOptions& o);
/** Ground truth of the scenario (calls buildWorld). Deterministic given world_seed.
 * Object poses xi_k use the g^o convention of object_pose.h relative to the first step at which
 * the object's centroid is within sensor range. */
io::TGroundTruth buildGroundTruth(const TScenarioOptions& o);
io::TGroundTruth groundTruthFromWorld(const TWorld& w, const TScenarioOptions& o);

struct TSimulatedRun
{
	std::vector<mrpt::obs::CActionCollection::Ptr> actions;  ///< ACT_k, k = 0..steps
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;       ///< SF_k
	/** Class ground truth of every reading, step by step in the order of the observations
	 * (B_gt_classes.csv, class_ground_truth.h). Not kept by simulateToRawlog. */
	std::vector<io::TReadingClass> classes;
};

/** Noisy odometry and measurements for the ground truth. Deterministic given noise_seed
 * (a fresh private MT19937 generator; seed 0 is a seed like any other). Throws
 * std::invalid_argument if noise_seed > 2^32 - 1. */
TSimulatedRun simulateMeasurements(const io::TGroundTruth& gt, const TScenarioOptions& o,
                                   uint64_t noise_seed);

/** Writes the run as a gz rawlog (format #1: a CObservationComment holding `comment` (if not
 * empty) and then ACT_k, SF_k for each step). Byte-identical for identical input. */
void writeRawlog(const TSimulatedRun& run, const std::string& path,
                 const std::string& comment = "");

/** The simulation of a long scenario streamed straight into a rawlog (no run kept in memory). */
void simulateToRawlog(const io::TGroundTruth& gt, const TScenarioOptions& o, uint64_t noise_seed,
                      const std::string& path, const std::string& comment = "");

/** Timestamp of step k (start_time + k dt) as MRPT stores it. */
mrpt::Clock::time_point stepTimestamp(const TScenarioOptions& o, size_t k);

/** Files for MRPT's kf-slam in dir: <base>_gt_landmarks.txt (CLandmarksMap::saveToTextFile
 * columns x y z type seenCount tLastSeen ID; static landmarks only), <base>_gt_robot_path.txt
 * (x y z yaw pitch roll) and <base>_gt_data_association.txt (rows: timestamp, index in
 * observation, true label = landmark ID), read by kf-slam's ground_truth_data_association.
 * The DA rows follow the observations of `run` (objects included). */
void writeKfSlamGroundTruth(const io::TGroundTruth& gt, const TSimulatedRun& run,
                            const std::string& dir, const std::string& base);
}  // namespace dynslam::sim
