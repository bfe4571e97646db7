#pragma once
/** @file object_drop.h
 * (Internal to dynslam::ekf.) The object-drop module (drop_object_after_unseen_steps > 0).
 * PlanDrops: every block of the objects due leaves the state; their poses (with the velocity)
 * and f_0 are recorded per record_dropped, the registry marks them dropped. It runs after the
 * drop policies planned theirs (which may have listed and recorded some of their blocks
 * already). */
#include <memory>
#include <vector>

#include "filter_module.h"

namespace dynslam::ekf
{
class CObjectDropModule : public IFilterModule
{
public:
	std::string name() const override { return "object_drop"; }
	unsigned hooks() const override { return hookBit(Hook::PlanDrops); }
	void planDrops(TFilterAccess& a, TPending& plan) override;
	/** The recorded f_0 of the dropped objects (record_dropped; getObjectFeatures). */
	const std::vector<TObjectFeatureEstimate>& droppedFeatures() const { return m_dropped; }

private:
	std::vector<TObjectFeatureEstimate> m_dropped;
	std::vector<bool> m_listed;  ///< scratch: the blocks already listed for removal
};

/** The module if drop_object_after_unseen_steps > 0 (null otherwise). */
std::unique_ptr<CObjectDropModule> makeObjectDropModule(TFilterAccess& a);
}  // namespace dynslam::ekf
