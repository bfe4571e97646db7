#pragma once
/** @file module_list.h
 * (Internal to dynslam::ekf.) The enabled capability modules of one CDynamicKFSLAM2D
 * (filter_module.h) and, per hook, the modules that take part in it. build() is the one place
 * that knows every module: it makes those the options enable, in the step's order. */
#include <array>
#include <memory>
#include <vector>

#include "filter_module.h"

namespace dynslam::ekf
{
class CLandmarkFusionModule;
class CObjectDropModule;
class CFirstEstimateModule;
class COdometryBiasModule;

class CModuleList
{
public:
	/** Makes the modules the filter's options and seams enable (reset(), after the seams and the
	 * drop policy); throws std::invalid_argument on a combination that cannot work. */
	void build(TFilterAccess& a);
	/** The enabled modules' names, in the order their hooks run. */
	std::vector<std::string> names() const;
	/** Hook calls since build() (a test sees that disabled capabilities are never called). */
	size_t hookCalls() const { return m_calls; }

	void afterRoute(TFilterAccess& a);
	void afterPropagate(TFilterAccess& a);
	void planDrops(TFilterAccess& a, TFilterAccess::TPending& plan);
	void afterCommit(TFilterAccess& a);
	void endOfStep(TFilterAccess& a);
	void staticForgotten(int32_t id);

	// the modules the facade's getters and the static update read (null: disabled)
	const CLandmarkFusionModule* fusion() const { return m_fusion; }
	const CObjectDropModule* objectDrop() const { return m_objectDrop; }
	const CFirstEstimateModule* firstEstimates() const { return m_firstEstimates; }
	/** The odometry bias (no hook: reset() and the prediction call it; it records timestamps). */
	COdometryBiasModule* odometryBias() const { return m_odometryBias; }

private:
	void add(std::unique_ptr<IFilterModule> m);
	const std::vector<IFilterModule*>& at(Hook h)
	{
		m_calls += m_hooks[size_t(h)].size();
		return m_hooks[size_t(h)];
	}
	std::vector<std::unique_ptr<IFilterModule>> m_modules;
	std::array<std::vector<IFilterModule*>, kHookCount> m_hooks;
	size_t m_calls = 0;
	CLandmarkFusionModule* m_fusion = nullptr;
	CObjectDropModule* m_objectDrop = nullptr;
	CFirstEstimateModule* m_firstEstimates = nullptr;
	COdometryBiasModule* m_odometryBias = nullptr;
};
}  // namespace dynslam::ekf
