#pragma once
/** @file consistency.h
 * NEES (normalized estimation error squared, needs ground truth) and NIS (normalized innovation
 * squared, from the filter) per block, for one run and averaged over N Monte Carlo runs, with
 * two-sided chi-square bounds (chi2.h). Definitions: doc/metrics.md.
 *
 * NEES of a block: eps = e^T P^-1 e, e = est - truth (angle wrapped), P the block's marginal
 * covariance. A block whose P is not positive definite (non-finite, or smallest eigenvalue
 * <= 1e-12 times the largest, e.g. the exactly known initial pose) is skipped and counted in
 * skipped_singular; no pseudo-inverse is used, so every kept sample has its full dof. (A
 * Cholesky factor whose estimated reciprocal condition number exceeds 1e-8 is used directly;
 * only less well conditioned blocks go through the eigenvalues.) */
#include <dynslam/eval/chi2.h>
#include <dynslam/eval/estimates.h>
#include <dynslam/io/ground_truth.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dynslam::eval
{
/** eps = e^T P^-1 e, or nullopt if P is not positive definite (see the file comment). */
std::optional<double> mahalanobis2(const Eigen::VectorXd& e, const Eigen::MatrixXd& P);

/** One NEES/NIS value: key = step (ego, object poses, NIS), landmark ID (landmarks) or 0
 * (whole map). */
struct TNeesSample
{
	int key = 0;
	double value = 0;
	int dof = 0;
};

/** The samples of one block type from one run. */
struct TNeesSamples
{
	std::vector<TNeesSample> samples;
	size_t skipped_singular = 0;
};

/** All NEES/NIS samples of one run. */
struct TRunConsistency
{
	TNeesSamples ego;            ///< key = step, 3 dof
	TNeesSamples landmarks;      ///< key = landmark ID, 2 dof, final estimates of IDs in the truth
	TNeesSamples map;            ///< one sample (key 0): all scored landmarks jointly, 2 L dof
	bool map_joint_cov = false;  ///< true: landmarks_cov used; false: block-diagonal
	std::map<int32_t, TNeesSamples> object_poses;  ///< object -> key = step, 3 or 2 dof
	TNeesSamples nis;  ///< key = step, dof from the filter; steps with 0 dof left out
};

/** Computes the NEES of every block against the truth, and copies the NIS. Steps/IDs missing
 * in the truth are left out (as in computeRunMetrics). */
TRunConsistency computeRunConsistency(const io::TGroundTruth& gt, const TRunEstimates& est);

/** One key (step or landmark) averaged over the runs that have it. */
struct TConsistencyRow
{
	int key = 0;
	int runs = 0;                 ///< N_k: runs with a sample at this key
	int total_dof = 0;            ///< n_k: sum of their dof (N_k n if all have n)
	double mean = 0;              ///< average NEES/NIS over those runs
	double lower = 0, upper = 0;  ///< chi2 quantiles of n_k at (1-c)/2, (1+c)/2, divided by N_k
	bool inside = false;
};

/** One block type over N runs (N = 1 for a single run). */
struct TConsistencyStats
{
	std::string name;
	double confidence = 0.95;
	std::vector<TConsistencyRow> rows;  ///< sorted by key
	size_t inside = 0;                  ///< rows inside their bounds
	double fraction_inside = kNaN;      ///< inside / rows.size()
	/** ANEES: sum of all values / sum of all dof (1 if consistent), and its two-sided bounds
	 * chi2 quantiles of the total dof D divided by D. */
	double anees = kNaN;
	double anees_lower = kNaN, anees_upper = kNaN;
	size_t skipped_singular = 0;  ///< summed over runs
};

/** Averages one block type over runs (pointers to each run's samples). */
TConsistencyStats aggregateConsistency(const std::string& name,
                                       const std::vector<const TNeesSamples*>& runs,
                                       double confidence = 0.95);

/** All blocks over N runs. */
struct TConsistencySummary
{
	int runs = 0;
	TConsistencyStats ego, landmarks, map, nis;
	bool map_joint_cov = false;  ///< true if every run gave a joint landmark covariance
	std::map<int32_t, TConsistencyStats> object_poses;
};

/** Summarizes N runs (all blocks). With one run it gives the single-run bounds. */
TConsistencySummary summarizeConsistency(const std::vector<TRunConsistency>& runs,
                                         double confidence = 0.95);
}  // namespace dynslam::eval
