#pragma once
/** @file ground_truth.h
 * Ground truth of a scenario (simulated or imported real data), independent of MRPT, and its
 * plain-text files. Written by dynslam-simulate and dynslam-mrclam beside the rawlog; read by
 * the apps and the evaluation. Step k of the ground truth is the pose after the k-th
 * (action, sensory frame) pair of the rawlog, i.e. the pose at which SF_k was taken.
 *
 * Files for base name B in a directory D (CSV with a header row; angles in radians):
 *  - D/B_gt_ego.csv              step,t,x,y,theta
 *  - D/B_gt_ego.tum              TUM: t x y z qx qy qz qw (for evo)
 *  - D/B_gt_landmarks.csv        id,x,y
 *  - D/B_gt_objects.csv          step,t,object,visible,first_step,dx,dy,dtheta
 *        object pose xi relative to its first sighting (g^o convention of object_pose.h:
 *        rotation about the time-0 centroid of all its features, then translation);
 *        dtheta = 0 for one-feature (translation-only) objects; NaN before first_step.
 *  - D/B_gt_object_features.csv  step,t,object,feature,id,x,y,visible
 * Readers reject malformed input with the file name and line number. */
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dynslam::io
{
struct TObjectGroundTruth
{
	int32_t object = -1;
	int num_features = 0;
	int first_step = -1;  ///< first step at which the object is observed (its time 0); -1: never
	std::vector<Eigen::Matrix2Xd> features;  ///< per step: 2 x num_features world positions
	std::vector<Eigen::Vector3d> pose;  ///< per step: xi relative to first sighting (NaN before)
	std::vector<uint8_t> visible;       ///< per step: 1 if observed at that step
	bool translationOnly() const { return num_features == 1; }
};

struct TGroundTruth
{
	std::vector<double> t;                         ///< per step [s]
	std::vector<Eigen::Vector3d> ego;              ///< per step: x, y, theta
	std::map<int32_t, Eigen::Vector2d> landmarks;  ///< static landmark ID -> position
	std::vector<TObjectGroundTruth> objects;       ///< ordered by object index
	size_t numSteps() const { return ego.size(); }
	/** Throws std::runtime_error if per-step vectors disagree in length. */
	void checkConsistent() const;
};

/** Writes the five files listed above into dir (created if missing). */
void writeGroundTruth(const TGroundTruth& gt, const std::string& dir, const std::string& base);
/** Reads them back. Throws std::runtime_error naming file and line on malformed input. */
TGroundTruth readGroundTruth(const std::string& dir, const std::string& base);

/** Ground truth in the plain-text formats of MRPT's simul-landmarks and kf-slam (static
 * landmarks only; lines starting with '%' or '#' and blank lines are comments):
 *  - robot path (simul-landmarks: <outFile>_ground_truth_robot_path.txt; kf-slam's
 *    ground_truth_file_robot; dynslam-simulate: <base>_gt_robot_path.txt): one row per sensory
 *    frame of the rawlog, 6 columns x y z yaw pitch roll (z, pitch, roll must be 0: 2-D);
 *  - landmarks (simul-landmarks: <outFile>_ground_truth.txt, CLandmarksMap::saveToTextFile;
 *    kf-slam's ground_truth_file; dynslam-simulate: <base>_gt_landmarks.txt): 7 columns
 *    x y z type seenCount tLastSeen ID (z must be 0).
 * Step k of the result is path row rowOfStep[k] (the rawlog pairing dropped some frames, see
 * rawlog_io.h) with time stepTimes[k]. Throws std::runtime_error naming file and line on
 * malformed input, and on a row count that is not rowsExpected. */
TGroundTruth readMrptGroundTruth(const std::string& pathFile, const std::string& landmarksFile,
                                 size_t rowsExpected, const std::vector<size_t>& rowOfStep,
                                 const std::vector<double>& stepTimes);
}  // namespace dynslam::io
