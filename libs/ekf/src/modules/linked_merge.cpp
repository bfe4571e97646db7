/** The linked-merge module (linked_merge.h). */
#include "linked_merge.h"

#include <dynslam/estimator/seam_registries.h>

#include "state_surgery.h"

namespace dynslam::ekf
{
std::unique_ptr<CLinkedMergeModule> makeLinkedMergeModule(TFilterAccess& a)
{
	// The options' router merges only if it classifies, with classify_merge_linked and an
	// object-centric model (makeSeams); a router set by setRouter may merge on its own.
	const auto& reg = estimator::routers();
	const std::string router = a.router().name();
	const bool merges =
	    a.userRouter() || (reg.has(router) && reg.caps(router).classifies &&
	                       a.options().classify.merge_linked && a.motion().objectCentric());
	if (!merges) return nullptr;
	return std::make_unique<CLinkedMergeModule>();
}

void CLinkedMergeModule::afterCommit(TFilterAccess& a)
{
	TStepReport& report = a.report();
	for (const auto& m : a.routed().merges)
		++(mergeObjects(a, m.from, m.into) ? report.objects_merged : report.merges_skipped);
}
}  // namespace dynslam::ekf
