#include <dynslam/estimator/drop_policy.h>

namespace dynslam::estimator
{
bool CDropPolicy::staticDue(int32_t id, int step, int addedStep) const
{
	const int N = m_opts.drop_static_after_unseen_steps;
	if (N <= 0) return false;
	const auto it = m_lastSeen.find(id);
	const int last = it == m_lastSeen.end() ? addedStep : it->second;
	return step - last >= N;
}

size_t CDropPolicy::posesToDrop(size_t numPoses) const
{
	const size_t K = size_t(m_opts.keep_last_poses < 1 ? 1 : m_opts.keep_last_poses);
	return numPoses > K ? numPoses - K : 0;
}
}  // namespace dynslam::estimator
