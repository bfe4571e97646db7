/** The enabled capability modules (module_list.h): which options enable which module, and the
 * dispatch of the step's hooks to them. */
#include "module_list.h"

#include "first_estimates.h"
#include "fusion.h"
#include "linked_merge.h"
#include "live_merge.h"
#include "object_drop.h"
#include "odometry_bias.h"

namespace dynslam::ekf
{
void CModuleList::add(std::unique_ptr<IFilterModule> m)
{
	if (!m) return;
	const unsigned bits = m->hooks();
	for (size_t h = 0; h < kHookCount; ++h)
		if (bits & hookBit(Hook(h))) m_hooks[h].push_back(m.get());
	m_modules.push_back(std::move(m));
}

void CModuleList::build(TFilterAccess& a)
{
	m_modules.clear();
	for (auto& h : m_hooks) h.clear();
	m_calls = 0;
	// In the step's order: a hook runs its modules in the order they are added here.
	auto bias = makeOdometryBiasModule(a);  // odometry_bias (no hook: the prediction calls it)
	m_odometryBias = bias.get();
	add(std::move(bias));
	auto fusion = makeLandmarkFusionModule(a);  // fuse_landmarks_prob
	m_fusion = fusion.get();
	add(std::move(fusion));
	auto fej = makeFirstEstimateModule(a);  // first_estimate_jacobians
	m_firstEstimates = fej.get();
	add(std::move(fej));
	auto drop = makeObjectDropModule(a);  // drop_object_after_unseen_steps
	m_objectDrop = drop.get();
	add(std::move(drop));
	add(makeLinkedMergeModule(a));  // classify_merge_linked
	add(makeLiveMergeModule(a));    // classify_merge_live
}

std::vector<std::string> CModuleList::names() const
{
	std::vector<std::string> out;
	for (const auto& m : m_modules) out.push_back(m->name());
	return out;
}

void CModuleList::afterRoute(TFilterAccess& a)
{
	for (IFilterModule* m : at(Hook::AfterRoute)) m->afterRoute(a);
}

void CModuleList::afterPropagate(TFilterAccess& a)
{
	for (IFilterModule* m : at(Hook::AfterPropagate)) m->afterPropagate(a);
}

void CModuleList::planDrops(TFilterAccess& a, TFilterAccess::TPending& plan)
{
	for (IFilterModule* m : at(Hook::PlanDrops)) m->planDrops(a, plan);
}

void CModuleList::afterCommit(TFilterAccess& a)
{
	for (IFilterModule* m : at(Hook::AfterCommit)) m->afterCommit(a);
}

void CModuleList::endOfStep(TFilterAccess& a)
{
	for (IFilterModule* m : at(Hook::EndOfStep)) m->endOfStep(a);
}

void CModuleList::staticForgotten(int32_t id)
{
	for (IFilterModule* m : at(Hook::StaticForgotten)) m->staticForgotten(id);
}
}  // namespace dynslam::ekf
