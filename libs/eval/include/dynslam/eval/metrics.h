#pragma once
/** @file metrics.h
 * Accuracy metrics of one run against ground truth, exactly as the columns of Table I of Chiu
 * (arXiv 2207.05043), plus the ego ATE and per-step errors with 3-sigma bounds. Definitions:
 * doc/metrics.md. All errors are estimate - truth, angles wrapped to (-pi, pi]. */
#include <dynslam/eval/estimates.h>
#include <dynslam/io/ground_truth.h>

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <vector>

namespace dynslam::eval
{
/** Root-mean-squared errors per component: x and y over n_xy samples, theta over n_theta
 * samples; NaN when there is no sample (theta is NaN for point quantities). */
struct TRmse
{
	double x = kNaN, y = kNaN, theta = kNaN;
	size_t n_xy = 0, n_theta = 0;
};

/** One ground-truth object (an "agent" of Table I). */
struct TObjectMetrics
{
	int32_t object = -1;
	bool translation_only = false;
	TRmse features;               ///< time-0 feature estimates vs truth at first_step (x, y)
	size_t features_missing = 0;  ///< ground-truth features with no estimate
	TRmse poses;  ///< over the steps with a pose estimate (x, y, theta; theta from 3-dof only)
	size_t poses_skipped = 0;  ///< pose estimates at steps outside the truth or before first_step
};

/** Table I metrics (and more) of one run. */
struct TRunMetrics
{
	TRmse ego;                       ///< over all estimated steps (x, y, theta)
	double ate = kNaN;               ///< sqrt(mean(ex^2 + ey^2)) over the same steps; no alignment
	double ate_aligned = kNaN;       ///< the same after the SE(2) least-squares alignment (align.h)
	size_t ego_skipped = 0;          ///< ego estimates at steps outside the ground truth
	TRmse static_map;                ///< final landmark estimates vs truth (x, y)
	size_t landmarks_missing = 0;    ///< ground-truth landmarks never estimated (excluded)
	size_t landmarks_unmatched = 0;  ///< estimated IDs not in the ground-truth static map
	std::vector<TObjectMetrics> objects;    ///< one per ground-truth object, in gt order
	size_t object_estimates_unmatched = 0;  ///< feature/pose estimates of unknown objects
	double ms_per_step = 0;                 ///< copied from the estimates
	/** Copied from the estimates' odometry_bias: b_w [rad/s] and s (NaN without a bias state,
	 * resp. without the scale); not part of the run records (run_records.h). */
	double odometry_bias_rate = kNaN, odometry_bias_scale = kNaN;
};

/** Pose error est - truth with the angle wrapped to (-pi, pi]. */
Eigen::Vector3d poseError(const Eigen::Vector3d& est, const Eigen::Vector3d& truth);

/** RMSE of a list of scalar errors (NaN if empty). */
double rmse(const std::vector<double>& errors);

/** Per-component RMSE of x, y and heading errors, with their counts. */
TRmse rmseOf(const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<double>& theta);

/** Computes all metrics of one run. Throws std::invalid_argument on malformed estimates
 * (checkEstimates) or ground truth whose per-step vectors disagree in length. */
TRunMetrics computeRunMetrics(const io::TGroundTruth& gt, const TRunEstimates& est);

/** One row of the per-step ego errors. */
struct TEgoErrorRow
{
	int step = 0;
	double t = kNaN;
	Eigen::Vector3d est, truth, error;  ///< error = est - truth (angle wrapped)
	Eigen::Vector3d sigma3;             ///< 3 sqrt(diag(cov))
};

/** Per-step ego errors with 3-sigma bounds, sorted by step; estimates at steps outside the
 * ground truth are left out. t is the estimate's t if finite, else gt.t[step]. */
std::vector<TEgoErrorRow> egoErrors(const io::TGroundTruth& gt,
                                    const std::vector<TEgoEstimate>& ego);

/** Throws std::invalid_argument if the ground truth's per-step vectors disagree in length
 * (t, ego, and each object's features/pose/visible) or an object has features of the wrong
 * size. (Same checks as io::TGroundTruth::checkConsistent, kept here to not depend on its IO.) */
void checkGroundTruth(const io::TGroundTruth& gt);
}  // namespace dynslam::eval
