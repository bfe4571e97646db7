#include <dynslam/estimator/state_lifecycle.h>

#include <stdexcept>

namespace dynslam::estimator
{
void CFullStateLifecycle::expandedCopy(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       const Eigen::Ref<const ekf::RowMatrixXd>& P,
                                       const CPaddedLayout& layout, Eigen::VectorXd& xo,
                                       ekf::RowMatrixXd& Po, CPaddedLayout& lo) const
{
	xo = x;
	Po = P;
	lo = layout;
}

CCompressedLifecycle::CCompressedLifecycle(int passive_after, int batch)
    : m_passiveAfter(passive_after), m_batch(batch)
{
	if (passive_after < 1 || batch < 1)
		throw std::invalid_argument("CCompressedLifecycle: passive_after (" +
		                            std::to_string(passive_after) + ") and batch (" +
		                            std::to_string(batch) + ") must be >= 1");
}

void CCompressedLifecycle::reset()
{
	m_levels.clear();
	m_passiveStatic.clear();
	m_nextLevel = 0;
}

bool CCompressedLifecycle::expansionNeeded(const std::vector<int32_t>& readIds,
                                           const std::function<bool(int32_t, int)>& due) const
{
	if (m_levels.empty()) return false;
	for (const int32_t id : readIds)
		if (m_passiveStatic.count(id)) return true;
	for (const auto& [id, step] : m_passiveStatic)
		if (due(id, step)) return true;
	return false;
}

void CCompressedLifecycle::expand(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout)
{
	if (m_levels.empty()) return;
	expandState(x, P, layout, m_levels);
	m_passiveStatic.clear();
}

void CCompressedLifecycle::expandedCopy(const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const Eigen::Ref<const ekf::RowMatrixXd>& P,
                                        const CPaddedLayout& layout, Eigen::VectorXd& xo,
                                        ekf::RowMatrixXd& Po, CPaddedLayout& lo) const
{
	xo = x;
	Po = P;
	lo = layout;
	if (m_levels.empty()) return;
	std::vector<TPassiveLevel> levels = m_levels;  // expandState consumes its levels
	expandState(xo, Po, lo, levels);
}

bool CCompressedLifecycle::compressIfDue(const Eigen::Ref<const Eigen::VectorXd>& x,
                                         const Eigen::Ref<const ekf::RowMatrixXd>& P,
                                         CPaddedLayout& layout,
                                         const std::function<int(const TBlock&)>& unseen,
                                         Eigen::VectorXd& xo, ekf::RowMatrixXd& Po)
{
	std::vector<bool> passive(layout.size(), false);
	int stale = 0;
	for (size_t b = 0; b < layout.size(); ++b)
	{
		const TBlock& t = layout[b];
		if (t.kind == BlockKind::Compressed)
			passive[b] = true;
		else if (t.kind == BlockKind::StaticLandmark && unseen(t) >= m_passiveAfter)
		{
			passive[b] = true;
			++stale;
		}
	}
	if (stale < m_batch) return false;
	for (size_t b = 0; b < layout.size(); ++b)
		if (passive[b] && layout[b].kind == BlockKind::StaticLandmark)
			m_passiveStatic[layout[b].id] = layout[b].step;
	m_levels.push_back(compressState(x, P, layout, passive, m_nextLevel++, xo, Po));
	return true;
}
}  // namespace dynslam::estimator
