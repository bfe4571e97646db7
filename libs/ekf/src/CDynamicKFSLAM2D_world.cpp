/** CDynamicKFSLAM2D: an object's velocity (object_model = cv | ctrv | ca; its world pose is
 * src/results/world_poses.cpp). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <algorithm>

#include "gauge/prior_gauge.h"
#include "results/world_blocks.h"

namespace dynslam
{
std::optional<TObjectVelocity> CDynamicKFSLAM2D::getObjectVelocity(int32_t object) const
{
	const estimator::TObjectEntry& e =
	    ekf::entryOf(m_router->registry(), object, "getObjectVelocity");
	const TStateRef s = wholeState();
	const ekf::TWorldBlocks o = ekf::worldBlocksOf(s.layout, object);
	if (o.vel == SIZE_MAX) return std::nullopt;
	// The velocity: the block's first poseDim entries (ca's block goes on with the acceleration).
	const std::vector<int> all = s.layout.indices(o.vel);
	const std::vector<int> idx(all.begin(), all.begin() + std::min<int>(e.poseDim(), all.size()));
	estimator::TBlock vel = s.layout[o.vel];
	vel.dim = int(idx.size());
	TObjectVelocity v;
	v.step = o.pose != SIZE_MAX ? s.layout[o.pose].step : m_step;
	v.mean = s.x(idx);
	v.cov = ekf::marginal(s.P, idx) + m_gauge->term(&vel, v.mean);
	return v;
}
}  // namespace dynslam
