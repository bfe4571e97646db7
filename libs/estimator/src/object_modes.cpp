#include <dynslam/estimator/object_modes.h>

#include <algorithm>

namespace dynslam::estimator
{
std::vector<std::string> modeNames(const IObjectMotionModel& model)
{
	std::vector<std::string> out;
	for (int j = 0; j < model.modeCount(); ++j) out.push_back(model.modeName(j));
	return out;
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
