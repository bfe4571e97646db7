#pragma once
/** @file robust_update_engines.h
 * Outlier handling behind the update seam (issue 17, doc/architecture.md), pure Eigen:
 *  - CRobustUpdateEngine: M-estimation of the linearised update by iteratively re-weighted
 *    least squares (IRLS) with a Huber or Cauchy kernel. Start with weights 1 (the plain sparse
 *    update); after each update, the residual of reading j at the updated state,
 *    r_j = nu_j - H_j (x+ - x-), gives d_j = sqrt(r_j^T R^-1 r_j) and the weight w_j = w(d_j);
 *    the update is redone from the prior with R_j = R / w_j, until the weights change by less
 *    than 1e-9 or `iterations` updates were made. No re-linearisation (the Jacobians and nu_j
 *    stay those of the prior estimate). No reading is ever discarded, so nothing can lock out:
 *    a large residual only lowers its reading's weight (Huber: c / d, Cauchy: 1/(1+(d/c)^2)).
 *    The gate threshold of the context is not used. With Huber and every d_j <= c the result is
 *    the plain sparse update exactly.
 *  - CGateRecoveryUpdateEngine: the chi-square gate of CSparseUpdateEngine plus a recovery
 *    rule. Per landmark it counts accepted readings and consecutive rejections; when a reading
 *    of a well-established landmark (>= min_updates accepted readings) is rejected for the
 *    count-th time in a row (or more), the ego block of P is inflated by `inflation`
 *    (P <- D P D, D = diag(sqrt(inflation) I3, I): PSD kept, ego-landmark correlations
 *    scaled by sqrt(inflation)) and the step's readings are gated again. The inflation repeats
 *    at every step while the rejections go on, so an ego error that the covariance does not
 *    admit is admitted after a bounded number of steps (the lock-out of MRCLAM robot 4). */
#include <dynslam/estimator/update_engine.h>

#include <map>

namespace dynslam::estimator
{
enum class RobustKernel
{
	Huber,
	Cauchy
};

/** Kernel weight w(d) of a residual of Mahalanobis length d >= 0 with parameter c > 0. */
double robustWeight(RobustKernel k, double d, double c);

class CRobustUpdateEngine : public IUpdateEngine
{
public:
	/** Throws std::invalid_argument if c <= 0 (or not finite) or iterations < 1. */
	CRobustUpdateEngine(RobustKernel kernel, double c, int iterations);
	std::string name() const override;
	TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                     const std::vector<TStaticObservation>& obs,
	                     const TUpdateContext& ctx) override;
	/** The weights used in the last update (one per reading, in order) and its update count. */
	const std::vector<double>& lastWeights() const { return m_weights; }
	int lastIterations() const { return m_iterations; }

private:
	RobustKernel m_kernel;
	double m_c;
	int m_maxIterations;
	std::vector<double> m_weights;
	int m_iterations = 0;
};

struct TGateRecoveryParams
{
	int count = 5;           ///< consecutive rejections that trigger the recovery (>= 1)
	double inflation = 4.0;  ///< factor on the ego covariance block per recovery (> 1)
	int min_updates = 3;     ///< accepted readings that make a landmark well established (>= 0)
};

class CGateRecoveryUpdateEngine : public IUpdateEngine
{
public:
	/** Throws std::invalid_argument on count < 1, inflation <= 1 or min_updates < 0. */
	explicit CGateRecoveryUpdateEngine(const TGateRecoveryParams& p);
	std::string name() const override { return "gate_recovery"; }
	/** ctx.gate_threshold must be finite (a gate to recover from); throws otherwise. */
	TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                     const std::vector<TStaticObservation>& obs,
	                     const TUpdateContext& ctx) override;
	size_t inflations() const { return m_inflations; }  ///< recoveries so far

private:
	TGateRecoveryParams m_p;
	std::map<int32_t, int> m_accepted, m_rejectedInARow;
	size_t m_inflations = 0;
};
}  // namespace dynslam::estimator
