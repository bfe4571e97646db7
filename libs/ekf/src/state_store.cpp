/** The state's lifecycle in the filter (state_store.h). */
#include "state_store.h"

namespace dynslam::ekf
{
void CStateStore::reset(bool active)
{
	m_active = active;
	m_valid = false;
}

void CStateStore::globalUpdate(TFilterAccess& a)
{
	estimator::IStateLifecycle& life = a.lifecycle();
	if (!life.holdsPassive()) return;
	Eigen::VectorXd x = a.mean();
	ekf::RowMatrixXd P = a.covBuffer().view();
	life.expand(x, P, a.editLayout());
	a.setWorkingState(x, P);
}

void CStateStore::startOfStep(TFilterAccess& a)
{
	if (!a.lifecycle().holdsPassive()) return;
	m_ids.clear();
	for (const auto& r : a.input().readings) m_ids.push_back(r.id);
	const int step = a.step();
	const estimator::CDropPolicy& drop = a.dropPolicy();
	if (a.lifecycle().expansionNeeded(m_ids, [&drop, step](int32_t id, int blockStep)
	                                  { return drop.due(id, step, blockStep); }))
		globalUpdate(a);
}

void CStateStore::endOfStep(TFilterAccess& a)
{
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	const int step = a.step();
	const estimator::CDropPolicy& drop = a.dropPolicy();
	const auto unseen = [&drop, step](const estimator::TBlock& t)
	{ return step - drop.lastSeen(t.id, t.step); };
	if (a.lifecycle().compressIfDue(std::as_const(a).mean(), a.covBuffer().view(), a.editLayout(),
	                                unseen, x, P))
		a.setWorkingState(x, P);
}

const TWholeState& CStateStore::expanded(const TFilterView& v) const
{
	if (m_valid && m_version == v.stateVersion()) return m_whole;
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	v.lifecycle().expandedCopy(v.mean(), v.cov(), v.layout(), x, P, m_whole.layout);
	m_whole.x.resize(size_t(x.size()));
	m_whole.x.asEigen() = x;
	m_whole.P.setSize(size_t(P.rows()), size_t(P.cols()));
	m_whole.P.asEigen() = P;
	TFilterView::slotsOf(m_whole.layout, m_whole.slots);
	m_valid = true;
	m_version = v.stateVersion();
	return m_whole;
}

CStateStore::TStateRef CStateStore::whole(const TFilterView& v) const
{
	if (!v.lifecycle().holdsPassive()) return {v.layout(), v.mean(), v.cov()};
	const TWholeState& w = expanded(v);
	return {w.layout, w.x.asEigen(), w.P.asEigen()};
}
}  // namespace dynslam::ekf
