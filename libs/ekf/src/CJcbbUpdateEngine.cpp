/** CJcbbUpdateEngine: MRPT's JCBB on the step's own landmarks, then the joint chi-square test
 * by branch and bound, then the sparse update of the accepted readings (CJcbbUpdateEngine.h). */
#include <dynslam/core/chi2.h>
#include <dynslam/ekf/CJcbbUpdateEngine.h>
#include <mrpt/slam/data_association.h>

#include <Eigen/Cholesky>
#include <stdexcept>

namespace dynslam
{
namespace
{
/// The step linearised at the prior: predictions, innovations and the joint S (2k x 2k).
struct TJointStep
{
	std::vector<Eigen::Vector2d> zhat, nu;
	Eigen::MatrixXd S;
};

TJointStep linearise(const Eigen::Ref<Eigen::VectorXd>& x, const Eigen::Ref<ekf::RowMatrixXd>& P,
                     const std::vector<estimator::TStaticObservation>& obs,
                     const estimator::TUpdateContext& ctx)
{
	TJointStep j;
	const Eigen::Index k = Eigen::Index(obs.size());
	const Eigen::Vector3d ego = x.head<3>();
	std::vector<int> idx{0, 1, 2};
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * k, 3 + 2 * k);
	for (Eigen::Index i = 0; i < k; ++i)
	{
		const auto& o = obs[size_t(i)];
		models::Matrix23d J_z_x;
		Eigen::Matrix2d J_z_f;
		const Eigen::Vector2d zhat = models::observe(
		    ctx.model, ego, Eigen::Vector2d(x[o.index], x[o.index + 1]), &J_z_x, &J_z_f);
		if (ctx.jacobians) ctx.jacobians(o.id, ego, J_z_x, J_z_f);
		j.zhat.push_back(zhat);
		j.nu.push_back(models::innovation(ctx.model, o.z, zhat));
		H.block<2, 3>(2 * i, 0) = J_z_x;
		H.block<2, 2>(2 * i, 3 + 2 * i) = J_z_f;
		idx.insert(idx.end(), {o.index, o.index + 1});
	}
	j.S = H * P(idx, idx) * H.transpose();
	for (Eigen::Index i = 0; i < k; ++i) j.S.block<2, 2>(2 * i, 2 * i) += ctx.R;
	return j;
}

/// Stage 1: MRPT's JCBB with the step's landmarks as the predictions; true for the readings
/// associated to their own landmark.
std::vector<bool> mrptJcbb(const TJointStep& j, double confidence)
{
	const size_t k = j.nu.size();
	mrpt::math::CMatrixDouble Z(k, 2), Y(k, 2), S(2 * k, 2 * k);
	for (size_t i = 0; i < k; ++i)
		for (int c = 0; c < 2; ++c)
		{
			Y(i, c) = j.zhat[i][c];
			// The reading expressed next to its own prediction (a bearing innovation wrapped
			// to (-pi, pi]); MRPT subtracts without wrapping.
			Z(i, c) = j.zhat[i][c] + j.nu[i][c];
		}
	S.asEigen() = j.S;
	mrpt::slam::TDataAssociationResults res;
	mrpt::slam::data_association_full_covariance(Z, Y, S, res, mrpt::slam::assocJCBB,
	                                             mrpt::slam::metricMaha, confidence, false);
	std::vector<bool> own(k, false);
	for (const auto& [o, p] : res.associations) own[o] = (o == p);
	return own;
}

/// Stage 2: the largest jointly compatible subset of `cand` (branch and bound).
class CJointSearch
{
public:
	CJointSearch(const TJointStep& j, std::vector<size_t> cand, double confidence, size_t maxNodes)
	    : m_j(j), m_cand(std::move(cand)), m_maxNodes(maxNodes)
	{
		m_threshold.push_back(0);
		for (size_t n = 1; n <= m_cand.size(); ++n)
			m_threshold.push_back(chi2Quantile(confidence, double(2 * n)));
	}
	void run()
	{
		std::vector<size_t> cur;
		recurse(0, cur, 0.0);
	}
	std::vector<size_t> best;
	double bestNis = 0;
	bool truncated = false;

private:
	double jointNis(const std::vector<size_t>& set) const
	{
		std::vector<int> rows;
		Eigen::VectorXd nu(2 * Eigen::Index(set.size()));
		for (size_t i = 0; i < set.size(); ++i)
		{
			rows.insert(rows.end(), {int(2 * set[i]), int(2 * set[i] + 1)});
			nu.segment<2>(2 * Eigen::Index(i)) = m_j.nu[set[i]];
		}
		const Eigen::MatrixXd Sa = m_j.S(rows, rows);
		return nu.dot(Sa.ldlt().solve(nu));
	}
	void recurse(size_t pos, std::vector<size_t>& cur, double nis)
	{
		if (++m_nodes > m_maxNodes)
		{
			truncated = true;
			return;
		}
		if (pos == m_cand.size())
		{
			if (cur.size() > best.size() || (cur.size() == best.size() && nis < bestNis))
			{
				best = cur;
				bestNis = nis;
			}
			return;
		}
		const size_t left = m_cand.size() - pos;
		if (cur.size() + left < best.size()) return;  // bound: cannot reach the best size
		cur.push_back(m_cand[pos]);
		const double withIt = jointNis(cur);
		if (withIt <= m_threshold[cur.size()]) recurse(pos + 1, cur, withIt);  // joint test
		cur.pop_back();
		if (cur.size() + left - 1 >= best.size()) recurse(pos + 1, cur, nis);
	}

	const TJointStep& m_j;
	std::vector<size_t> m_cand;
	std::vector<double> m_threshold;  ///< [n]: chi2 quantile with 2n dof
	size_t m_maxNodes, m_nodes = 0;
};
}  // namespace

CJcbbUpdateEngine::CJcbbUpdateEngine(double confidence, size_t max_nodes)
    : m_confidence(confidence), m_maxNodes(max_nodes)
{
	if (!(confidence > 0 && confidence < 1))
		throw std::invalid_argument(
		    "CJcbbUpdateEngine: confidence = " + std::to_string(confidence) +
		    " must be a probability in (0, 1) (innovation_gate)");
	if (max_nodes < 1) throw std::invalid_argument("CJcbbUpdateEngine: max_nodes must be >= 1");
}

estimator::TUpdateResult CJcbbUpdateEngine::update(
    Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
    const std::vector<estimator::TStaticObservation>& obs, const estimator::TUpdateContext& ctx)
{
	m_accepted.assign(obs.size(), false);
	m_mrptAssociated = 0;
	m_jointNis = 0;
	if (obs.empty()) return {};  // documented: a no-op
	const TJointStep j = linearise(x, P, obs, ctx);
	const std::vector<bool> own = mrptJcbb(j, m_confidence);
	const double gate = estimator::gateThreshold2Dof(m_confidence);
	std::vector<size_t> cand;
	for (size_t i = 0; i < obs.size(); ++i)
	{
		if (!own[i]) continue;
		++m_mrptAssociated;
		const Eigen::Matrix2d Si = j.S.block<2, 2>(2 * Eigen::Index(i), 2 * Eigen::Index(i));
		if (j.nu[i].dot(Si.ldlt().solve(j.nu[i])) <= gate) cand.push_back(i);
	}
	CJointSearch search(j, cand, m_confidence, m_maxNodes);
	search.run();
	if (search.truncated) ++m_truncated;
	std::vector<estimator::TStaticObservation> use;
	for (size_t i : search.best)
	{
		m_accepted[i] = true;
		use.push_back(obs[i]);
	}
	m_jointNis = search.bestNis;
	estimator::TUpdateContext plain = ctx;
	plain.gate_threshold = std::numeric_limits<double>::infinity();
	estimator::TUpdateResult r = m_sparse.update(x, P, use, plain);
	r.gated_out = obs.size() - use.size();
	return r;
}
}  // namespace dynslam
