#pragma once
/** @file live_merge.h
 * The test that two live objects A and B (both in the filter, both seen) move as one rigid body
 * (classify_merge_live, doc/results/classification.md "Merging two live objects"). The filter hands
 * it, at every step at which both are seen, y = B's features expressed in A's frame (the merge's
 * own map, models::mergeObjectFeatures: constant when they are one body) with its covariance S from
 * the filter's joint covariance, and (object-centric models) the chi-square of the velocity
 * residual (models::rigidVelocityResidual). Over the pair's last W observations:
 *
 * - Wald's SPRT of "one body" (y constant) against "two bodies" (y a random walk with
 *   classify_motion_std sigma_m per step and coordinate): the log-likelihood ratio of an
 *   increment delta = y_k - y_(k-1), g steps apart, C = S_k + S_(k-1) (the cross-time covariance
 *   is not tracked), is log N(delta; 0, C) - log N(delta; 0, C + sigma_m^2 g I); "one body" when
 *   the sum over the window reaches log((1 - beta) / alpha), alpha = classify_merge_live_alpha
 *   (the false-merge probability), beta = classify_beta;
 * - no steady drift: the weighted least-squares slope b of y over the window's steps
 *   (y_i = a + b t_i + e_i, e_i ~ N(0, S_i) independent), b^T Cov(b)^-1 b within the chi-square
 *   quantile (2 m dof) at classify_group_prob (the grouping's rigid test level);
 * - the velocities agree now: the velocity residual's chi-square within that quantile.
 *
 * Pure Eigen; no MRPT. */
#include <dynslam/estimator/classifying_router.h>

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <utility>

namespace dynslam::estimator
{
struct TLiveMergeParams
{
	int window = 5;            ///< classify_merge_live_window: increments per decision, >= 1
	double alpha = 1e-3;       ///< the SPRT's false-merge probability, (0, 1) (no INI key)
	double beta = 0.01;        ///< classify_beta
	double motion_std = 0.5;   ///< classify_motion_std [m per step]
	double rigid_prob = 0.99;  ///< classify_group_prob
};

/** One observation of a pair. */
struct TLiveMergeSample
{
	int step = 0;
	Eigen::VectorXd y;    ///< B's features in A's frame (2 m)
	Eigen::MatrixXd S;    ///< their covariance
	double vel_chi2 = 0;  ///< the velocity residual's chi-square (0 without velocities)
	int vel_dof = 0;      ///< its dimension (0: none)
};

/** What the last observation of a pair gave (for tests and reports). */
struct TLiveMergeStats
{
	double llr = 0;         ///< the SPRT sum over the window
	double drift_chi2 = 0;  ///< the window's end-to-end chi-square
	int increments = 0;     ///< increments in the window
	bool rigid = false;     ///< the decision: merge
};

class CLiveMergeDetector
{
public:
	explicit CLiveMergeDetector(const TLiveMergeParams& p = {});
	/** Adds an observation of the pair (a, b) and returns the decision. A sample of another size
	 * than the pair's previous one (a feature joined) restarts the pair's window. */
	TLiveMergeStats observe(int32_t a, int32_t b, const TLiveMergeSample& s);
	/** Forgets every pair not observed since step - keep (objects that left). */
	void prune(int step, int keep);
	void reset() { m_pairs.clear(); }
	size_t pairs() const { return m_pairs.size(); }
	int window() const { return m_p.window; }
	/** The log-likelihood ratio of one increment (one body against two), exposed for tests. */
	static double incrementLlr(const Eigen::VectorXd& delta, const Eigen::MatrixXd& C,
	                           double spread2);
	/** The chi-square of the weighted least-squares slope of y over the samples' steps (0 with
	 * fewer than 3 samples), exposed for tests. */
	static double trendChi2(const std::deque<TLiveMergeSample>& samples);

private:
	struct TPair
	{
		std::deque<TLiveMergeSample> samples;  ///< the last window + 1 observations
		std::deque<double> llr;                ///< the LLR of each increment among them
	};
	TLiveMergeParams m_p;
	std::map<std::pair<int32_t, int32_t>, TPair> m_pairs;
};

/** The detector of classify_merge_live (null when it is off). Window 0 (automatic): 5 with an
 * object-centric model, 20 with the paper's, whose pose noise Sigma_xi dominates the statistic's
 * covariance (doc/results/classification.md "Merging two live objects"). */
std::unique_ptr<CLiveMergeDetector> makeLiveMergeDetector(const TClassifyParams& c,
                                                          bool objectCentric);
}  // namespace dynslam::estimator
