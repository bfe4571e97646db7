#pragma once
/** @file estimates.h
 * The estimates of one filter run, as plain data (no dependency on any filter class). The apps
 * fill these from CDynamicKFSLAM2D, from mrpt::slam::CRangeBearingKFSLAM2D, or from files;
 * the metrics (metrics.h, consistency.h), writers (writers.h) and figures (figures.h) read them.
 *
 * Conventions (the same as dynslam::io::TGroundTruth, ground_truth.h):
 *  - step k is the pose after the k-th (action, sensory frame) pair of the rawlog;
 *  - angles in radians; pad entries of the filter state never appear here;
 *  - object poses are xi = (dx, dy, dtheta) relative to the object's first sighting (g^o of
 *    object_pose.h: rotation about the time-0 centroid of its features, then translation), or
 *    (dx, dy) for translation-only (one-feature) objects;
 *  - object features are the time-0 estimates f_0 (position at the object's first sighting). */
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace dynslam::eval
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/** Ego pose estimate (x, y, theta) and its 3x3 marginal covariance at one step. */
struct TEgoEstimate
{
	int step = 0;
	Eigen::Vector3d mean = Eigen::Vector3d::Zero();
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
	/** Time stamp [s]; NaN if unknown (writers then use the ground truth's t[step]). */
	double t = std::numeric_limits<double>::quiet_NaN();
};

/** Final estimate of one static landmark (world frame). */
struct TLandmarkEstimate
{
	int32_t id = -1;
	Eigen::Vector2d mean = Eigen::Vector2d::Zero();
	Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
};

/** Time-0 estimate f_0 of feature `feature` (0-based index within the object) of object
 * `object` (io::TObjectGroundTruth::object), compared with the object's ground-truth features at
 * its first_step. */
struct TObjectFeatureEstimate
{
	int32_t object = -1;
	int32_t feature = -1;
	Eigen::Vector2d mean = Eigen::Vector2d::Zero();
	Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
};

/** Pose xi of object `object` at step `step`, relative to its first sighting: 3-dof
 * (dx, dy, dtheta) or 2-dof (dx, dy) for translation-only objects. cov is 3x3 or 2x2. */
struct TObjectPoseEstimate
{
	int32_t object = -1;
	int step = 0;
	Eigen::VectorXd mean;
	Eigen::MatrixXd cov;
	/** Velocity at that step of a model with a velocity state (object_model = cv | ctrv:
	 * world-frame (vx, vy) of the reference point, and omega for 3-dof poses) and its
	 * covariance; empty otherwise (velocity_metrics.h). */
	Eigen::VectorXd velocity;
	Eigen::MatrixXd velocity_cov;
	/** object_model = mm: mode probabilities at that step (TRunEstimates::object_mode_names). */
	Eigen::VectorXd mode_probabilities;
};

/** Everything one run produced. */
struct TRunEstimates
{
	std::vector<TEgoEstimate> ego;             ///< one per processed step, any order, unique steps
	std::vector<TLandmarkEstimate> landmarks;  ///< final static map (unique IDs)
	/** Optional joint covariance of all landmarks, 2L x 2L, in the order of `landmarks`
	 * (rows 2i, 2i+1 = landmarks[i]). Empty: unknown; the whole-map NEES then uses the
	 * block-diagonal of the marginal covariances (reported as such). */
	Eigen::MatrixXd landmarks_cov;
	std::vector<TObjectFeatureEstimate> object_features;
	std::vector<TObjectPoseEstimate> object_poses;
	/** The modes of TObjectPoseEstimate::mode_probabilities (empty: a single model). */
	std::vector<std::string> object_mode_names;
	/** Per step k (index = step): NIS of all measurements used in the update at step k, with
	 * its degrees of freedom nis_dof[k] (2 x number of associations); 0 dof = no update. */
	std::vector<double> nis;
	std::vector<int> nis_dof;
	double ms_per_step = 0;  ///< mean wall time per step [ms]
	/** Final odometry bias estimate of a filter with a bias state (odometry_bias = rate: (b_w)
	 * [rad/s]; rate_scale: (b_w, s)); empty without one. */
	Eigen::VectorXd odometry_bias;
};

/** Checks sizes and finiteness of means: unique ego steps >= 0, object pose mean of size 2 or 3
 * with a matching covariance, landmarks_cov empty or 2L x 2L, nis and nis_dof of equal length.
 * Throws std::invalid_argument naming the offending entry. */
void checkEstimates(const TRunEstimates& est);

/** Mean entries beyond this magnitude (1e9 m, far beyond any map; or rad) mark a diverged filter.
 */
constexpr double kDivergedMagnitude = 1e9;
/** The first mean with an entry that is not finite or beyond kDivergedMagnitude (a filter that
 * diverged), described as "ego mean at step k", "mean of landmark ID", "mean of object o
 * feature f" or "pose of object o at step k"; empty when every mean is sane. Searched in that
 * order. */
std::string divergedEstimate(const TRunEstimates& est);
}  // namespace dynslam::eval
