#include <dynslam/estimator/drop_policy.h>

namespace dynslam::estimator
{
void CDropPolicy::noteSeen(int32_t id, int step)
{
	const auto [it, fresh] = m_seen.try_emplace(id);
	TSeen& s = it->second;
	if (fresh) s.first = step;
	s.last = step;
	if (m_opts.prune_min_sightings > 0 && step - s.first < m_opts.prune_window) ++s.count;
}

bool CDropPolicy::staticDue(int32_t id, int step, int addedStep) const
{
	const int N = m_opts.drop_static_after_unseen_steps;
	if (N <= 0) return false;
	const auto it = m_seen.find(id);
	const int last = it == m_seen.end() ? addedStep : it->second.last;
	return step - last >= N;
}

bool CDropPolicy::pruneDue(int32_t id, int step, int addedStep) const
{
	const int k = m_opts.prune_min_sightings;
	if (k <= 0) return false;
	const auto it = m_seen.find(id);
	const int first = it == m_seen.end() ? addedStep : it->second.first;
	const int count = it == m_seen.end() ? 0 : it->second.count;
	// The window is the steps first .. first + W - 1; decided at the end of its last step.
	return count < k && step - first >= m_opts.prune_window - 1;
}

bool CDropPolicy::objectDue(int32_t obj, int step, int firstStep) const
{
	const int N = m_opts.drop_object_after_unseen_steps;
	if (N <= 0) return false;
	const auto it = m_objectSeen.find(obj);
	return step - (it == m_objectSeen.end() ? firstStep : it->second) >= N;
}

size_t CDropPolicy::posesToDrop(size_t numPoses) const
{
	const size_t K = size_t(m_opts.keep_last_poses < 1 ? 1 : m_opts.keep_last_poses);
	return numPoses > K ? numPoses - K : 0;
}
}  // namespace dynslam::estimator
