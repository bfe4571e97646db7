/** CDynamicKFSLAM2D: the compressed EKF (static_update = compressed; the math in
 * dynslam/estimator/compressed_state.h). The step runs unchanged on the working state (ego,
 * objects, static landmarks seen recently, and the compressed entries); static landmarks unseen
 * for a while are taken out at the end of a step, and everything is brought up to date (the
 * global update) when one of them is read again, is due to be dropped, or a getter of the whole
 * state is called. */
#include <dynslam/CDynamicKFSLAM2D.h>

namespace dynslam
{
using estimator::BlockKind;

namespace
{
void readState(const CDynamicKFSLAM2D::KFVector& xs, const ekf::CSquareBuffer& Ps,
               Eigen::VectorXd& x, ekf::RowMatrixXd& P)
{
	x = xs.asEigen();
	P = Ps.view();
}
}  // namespace

void CDynamicKFSLAM2D::globalUpdate()
{
	if (m_passive.empty()) return;
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	readState(m_xkk, m_cov, x, P);
	estimator::expandState(x, P, m_layout, m_passive);
	m_xkk.resize(size_t(x.size()));
	m_xkk.asEigen() = x;
	setCov(P);
	m_passiveStatic.clear();
	onLayoutChanged();
}

void CDynamicKFSLAM2D::ensureExpanded() const
{
	// The global update changes how the estimate is stored, not the estimate: a getter may do it.
	if (!m_passive.empty()) const_cast<CDynamicKFSLAM2D*>(this)->globalUpdate();
}

void CDynamicKFSLAM2D::expandIfNeeded()
{
	if (m_passive.empty()) return;
	bool need = false;
	for (const auto& r : m_in.readings) need = need || m_passiveStatic.count(r.id) != 0;
	for (const auto& [id, step] : m_passiveStatic)
		need = need || m_drop.staticDue(id, m_step, step);
	if (need) globalUpdate();
}

void CDynamicKFSLAM2D::compressIfDue()
{
	const auto* engine = dynamic_cast<const estimator::CCompressedUpdateEngine*>(m_engine.get());
	if (!engine) return;
	std::vector<bool> passive(m_layout.size(), false);
	int stale = 0;
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const estimator::TBlock& t = m_layout[b];
		if (t.kind == BlockKind::Compressed)
			passive[b] = true;
		else if (t.kind == BlockKind::StaticLandmark &&
		         m_step - m_drop.lastSeen(t.id, t.step) >= engine->passiveAfter())
		{
			passive[b] = true;
			++stale;
		}
	}
	if (stale < engine->batch()) return;
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	for (size_t b = 0; b < m_layout.size(); ++b)
		if (passive[b] && m_layout[b].kind == BlockKind::StaticLandmark)
			m_passiveStatic[m_layout[b].id] = m_layout[b].step;
	m_passive.push_back(estimator::compressState(m_xkk.asEigen(), m_cov.view(), m_layout, passive,
	                                             m_nextLevel++, x, P));
	m_xkk.resize(size_t(x.size()));
	m_xkk.asEigen() = x;
	setCov(P);
	onLayoutChanged();
}
}  // namespace dynslam
