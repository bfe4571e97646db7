/** CDynamicKFSLAM2D: the state's lifecycle (estimator::IStateLifecycle; the compressed EKF of
 * static_update = compressed is estimator::CCompressedLifecycle, its math
 * dynslam/estimator/compressed_state.h). The step runs unchanged on the working state; the
 * lifecycle may take entries out of it at the end of a step and needs them back (the global
 * update) when one is read again or is due to be dropped. Getters of the whole state read an
 * expanded copy and leave the working state as it is. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

namespace dynslam
{
void CDynamicKFSLAM2D::writeWorkingState(const Eigen::VectorXd& x, const ekf::RowMatrixXd& P)
{
	m_xkk.resize(size_t(x.size()));
	m_xkk.asEigen() = x;
	setCov(P);
	onLayoutChanged();
}

void CDynamicKFSLAM2D::globalUpdate()
{
	if (!m_lifecycle->holdsPassive()) return;
	Eigen::VectorXd x = m_xkk.asEigen();
	ekf::RowMatrixXd P = m_cov.view();
	m_lifecycle->expand(x, P, m_layout);
	writeWorkingState(x, P);
}

void CDynamicKFSLAM2D::expandIfNeeded()
{
	if (!m_lifecycle->holdsPassive()) return;
	std::vector<int32_t>& ids = m_idScratch;
	ids.clear();
	for (const auto& r : m_in.readings) ids.push_back(r.id);
	if (m_lifecycle->expansionNeeded(
	        ids, [this](int32_t id, int blockStep) { return m_drop.due(id, m_step, blockStep); }))
		globalUpdate();
}

void CDynamicKFSLAM2D::compressIfDue()
{
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	const auto unseen = [this](const estimator::TBlock& t)
	{ return m_step - m_drop.lastSeen(t.id, t.step); };
	if (m_lifecycle->compressIfDue(m_xkk.asEigen(), m_cov.view(), m_layout, unseen, x, P))
		writeWorkingState(x, P);
}

const CDynamicKFSLAM2D::TWholeState& CDynamicKFSLAM2D::whole() const
{
	if (m_whole.valid) return m_whole;
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	m_lifecycle->expandedCopy(m_xkk.asEigen(), m_cov.view(), m_layout, x, P, m_whole.layout);
	m_whole.x.resize(size_t(x.size()));
	m_whole.x.asEigen() = x;
	m_whole.P.setSize(size_t(P.rows()), size_t(P.cols()));
	m_whole.P.asEigen() = P;
	slotsOf(m_whole.layout, m_whole.slots, nullptr);
	m_whole.valid = true;
	return m_whole;
}

CDynamicKFSLAM2D::TStateRef CDynamicKFSLAM2D::wholeState() const
{
	if (!m_lifecycle->holdsPassive()) return {m_layout, m_xkk.asEigen(), m_cov.view()};
	const TWholeState& w = whole();
	return {w.layout, w.x.asEigen(), w.P.asEigen()};
}
}  // namespace dynslam
