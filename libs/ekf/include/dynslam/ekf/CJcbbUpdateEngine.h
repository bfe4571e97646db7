#pragma once
/** @file CJcbbUpdateEngine.h
 * Joint compatibility of a step's static readings (outlier_method = jcbb; issue 17,
 * doc/results/real-data.md 5.9): a single bad reading can neither pass nor block the set.
 *
 * The readings carry known IDs, so the candidate prediction of each reading is the predicted
 * reading of its own ID's landmark: the predictions are the step's own landmarks, one per
 * reading, with their full joint innovation covariance S = H P H^T + R (ego and landmark
 * correlations included). Two stages:
 *  1. MRPT's JCBB, mrpt::slam::data_association_full_covariance(assocJCBB, metricMaha) on
 *     these predictions: individual compatibility (MRPT's chi2inv of the confidence, 2 dof)
 *     of every reading with every prediction of the step, then the hypothesis with the most
 *     pairings (ties: the smallest joint Mahalanobis distance). A reading left unassociated,
 *     or associated to another reading's landmark (its ID disagrees with its position), is
 *     rejected. MRPT 2.5.8's JCBB does NOT test the joint compatibility of a hypothesis (its
 *     recursion only counts pairings; checked: it associates a pair whose joint NIS is 58
 *     against chi2inv(0.99, 4) = 13.3, tests/ekf/test_jcbb.cpp), so:
 *  2. the joint chi-square test, by branch and bound over the readings stage 1 kept that also
 *     pass the individual gate (exact quantile; MRPT's chi2inv is Wilson-Hilferty, looser:
 *     14.13 against 13.82 at 0.999, 2 dof): the largest subset A whose joint NIS
 *     nu_A^T S_AA^-1 nu_A <= chi2Quantile(confidence, 2 |A|), built in observation order and
 *     jointly compatible at every step of the branch (Neira and Tardos 2001); among subsets of
 *     that size the smallest joint NIS (ties: the first found, earlier readings first).
 *     A search that explores more than max_nodes nodes stops with the best subset so far
 *     (counted: searchesTruncated()).
 * The accepted readings are then used by CSparseUpdateEngine (no gate); the others are
 * counted as TUpdateResult::gated_out. The accepted set is always a subset of what the
 * individual gate at the same confidence accepts, and equal to it when the step is jointly
 * compatible and no reading is closer (jointly) to another reading's landmark than to its own
 * (then the result equals the gated sparse update). ctx.gate_threshold is not
 * used: the confidence is the engine's. An empty step is a no-op (nothing changed, zero
 * counts). Complexity: O(2^k) nodes at worst for k readings; O(k) when the step is jointly
 * compatible, O(k^2) with one outlier. */
#include <dynslam/estimator/update_engine.h>

namespace dynslam
{
class CJcbbUpdateEngine : public estimator::IUpdateEngine
{
public:
	/** confidence: the chi-square probability of the individual and joint tests (the INI's
	 * innovation_gate). Throws std::invalid_argument unless 0 < confidence < 1 and
	 * max_nodes >= 1. */
	explicit CJcbbUpdateEngine(double confidence, size_t max_nodes = 100000);
	std::string name() const override { return "jcbb"; }
	estimator::TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                                const std::vector<estimator::TStaticObservation>& obs,
	                                const estimator::TUpdateContext& ctx) override;

	/** Of the last update, per reading in order: accepted (used in the update) or not. */
	const std::vector<bool>& lastAccepted() const { return m_accepted; }
	/** Of the last update: readings MRPT's JCBB (stage 1) associated to their own landmark. */
	size_t lastMrptAssociated() const { return m_mrptAssociated; }
	/** Of the last update: the joint NIS of the accepted readings (0 if none). */
	double lastJointNis() const { return m_jointNis; }
	size_t searchesTruncated() const { return m_truncated; }
	double confidence() const { return m_confidence; }

private:
	double m_confidence;
	size_t m_maxNodes;
	estimator::CSparseUpdateEngine m_sparse;
	std::vector<bool> m_accepted;
	size_t m_mrptAssociated = 0, m_truncated = 0;
	double m_jointNis = 0;
};
}  // namespace dynslam
