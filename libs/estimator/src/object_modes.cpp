#include <dynslam/estimator/object_modes.h>

#include <algorithm>
#include <stdexcept>

namespace dynslam::estimator
{
std::vector<std::string> modeNames(const IObjectMotionModel& model)
{
	std::vector<std::string> out;
	for (int j = 0; j < model.modeCount(); ++j) out.push_back(model.modeName(j));
	return out;
}

Eigen::VectorXd readingsModeLogLikelihoods(const TModePredictions& pred, const Eigen::MatrixXd& P_e,
                                           Eigen::Index poseDim, Eigen::Index m,
                                           const Eigen::Matrix2d& Sigma_v,
                                           const TSightingFn& sighting)
{
	if (m == 0) return Eigen::VectorXd();
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * m, 2 * m);
	for (Eigen::Index r = 0; r < m; ++r) R.block(2 * r, 2 * r, 2, 2) = Sigma_v;
	Eigen::VectorXd logL(Eigen::Index(pred.s.size()));
	for (size_t j = 0; j < pred.s.size(); ++j)
	{
		const Eigen::Index ns = pred.s[j].size(), nf = P_e.cols() - 3 - ns;
		if (poseDim > ns || nf < 0)
			throw std::invalid_argument("readingsModeLogLikelihoods: sizes do not match");
		const Eigen::VectorXd xi = pred.s[j].head(poseDim);
		Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * m, P_e.cols());
		Eigen::VectorXd nu(2 * m);
		for (Eigen::Index r = 0; r < m; ++r)
		{
			const TReadingSighting z = sighting(r, xi);
			if (z.H_xi.rows() != 2 || z.H_xi.cols() != poseDim || z.H_f0.rows() != 2 ||
			    z.H_f0.cols() != nf)
				throw std::invalid_argument(
				    "readingsModeLogLikelihoods: a sighting's Jacobian "
				    "sizes do not match");
			H.block(2 * r, 0, 2, 3) = z.H_x;
			H.block(2 * r, 3, 2, poseDim) = z.H_xi;  // the velocity's columns stay 0
			H.block(2 * r, 3 + ns, 2, nf) = z.H_f0;
			nu.segment(2 * r, 2) = z.nu;
		}
		logL[Eigen::Index(j)] =
		    models::predictedReadingsLogLikelihood(P_e, 3, pred.F[j], pred.Q[j], H, nu, R);
	}
	return logL;
}

models::TModeMixture CObjectModes::predict(const IObjectMotionModel& model, int32_t obj, int step,
                                           const Eigen::VectorXd& s, const Eigen::MatrixXd& P_ss,
                                           const TLogLikelihoods& logLikelihoods, bool record)
{
	const int M = model.modeCount();
	auto it = m_prob.find(obj);
	if (it == m_prob.end()) it = m_prob.emplace(obj, model.initialModeProbabilities()).first;
	TModePredictions pred;
	pred.s.resize(size_t(M));
	pred.F.resize(size_t(M));
	pred.Q.resize(size_t(M));
	for (int j = 0; j < M; ++j)
		pred.s[size_t(j)] = model.predictMode(j, s, &pred.F[size_t(j)], &pred.Q[size_t(j)]);
	it->second = models::modePosterior(it->second, model.modeTransition(), logLikelihoods(pred));
	auto& history = m_history[obj];
	if (!record) history.clear();  // record_dropped = false: the newest only
	history.emplace_back(step, it->second);
	const Eigen::Index d = s.size() / 2;
	return models::mixModes(pred.s, pred.F, pred.Q, models::prunedWeights(it->second), P_ss,
	                        d == 3 ? 2 : -1);
}

const Eigen::VectorXd* CObjectModes::at(int32_t obj, int step) const
{
	const auto h = m_history.find(obj);
	if (h == m_history.end()) return nullptr;
	const auto it = std::lower_bound(h->second.begin(), h->second.end(), step,
	                                 [](const auto& a, int k) { return a.first < k; });
	return it != h->second.end() && it->first == step ? &it->second : nullptr;
}

void CObjectModes::forget(const std::set<int32_t>& live)
{
	for (auto it = m_prob.begin(); it != m_prob.end();)
		it = live.count(it->first) ? std::next(it) : m_prob.erase(it);
}

void CObjectModes::clear()
{
	m_prob.clear();
	m_history.clear();
}
}  // namespace dynslam::estimator
