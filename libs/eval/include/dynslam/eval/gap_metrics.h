#pragma once
/** @file gap_metrics.h
 * The ego inside landmark gaps (issue 13; doc/metrics.md "Inside a landmark gap"): the ATE over
 * the steps whose true ego x lies in a gap (the highway scenarios run along x), over the other
 * steps, the position error at the last gap step, and the mean ego NEES (3 dof) over the gap
 * steps with its two-sided 95 % chi-square bounds. Pure Eigen. */
#include <dynslam/eval/estimates.h>
#include <dynslam/io/ground_truth.h>

#include <utility>
#include <vector>

namespace dynslam::eval
{
struct TGapMetrics
{
	size_t steps = 0;  ///< gap steps with an ego estimate
	double ate = kNaN, ate_outside = kNaN;
	double err_end = kNaN;  ///< position error at the last gap step with an estimate
	/** Mean NEES over the gap steps with a positive-definite covariance (nees_steps of them)
	 * and the 2.5 / 97.5 % quantiles of chi2(3 n) / n. */
	double nees = kNaN, nees_lower = kNaN, nees_upper = kNaN;
	size_t nees_steps = 0;
};

/** Gaps are [start, end] on the true ego x (start < end). Steps outside the ground truth are
 * ignored. No gap step: steps = 0 and NaN gap values. */
TGapMetrics gapMetrics(const io::TGroundTruth& gt, const std::vector<TEgoEstimate>& ego,
                       const std::vector<std::pair<double, double>>& gaps);
}  // namespace dynslam::eval
