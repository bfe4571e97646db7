/** Results: the objects' pose histories and the live-object count (reader.h). */
#include <dynslam/common/backend_results.h>
#include <dynslam/core/ekf_steps.h>

#include <algorithm>

#include "../gauge/prior_gauge.h"
#include "reader.h"

namespace dynslam::ekf::results
{
using estimator::BlockKind;
using estimator::TBlock;

std::map<int32_t, TObjectTrack> objectTracks(const TFilterView& v)
{
	const CPriorGauge& gauge = v.gauge();
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(v.objects());
	for (auto& [obj, track] : out)  // dropped poses: recorded with the relative covariance
		for (TObjectPoseEstimate& e : track.poses)
		{
			TBlock pose;
			pose.kind = BlockKind::ObjectPose;
			pose.dim = int(e.mean.size());
			e.cov += gauge.term(&pose, e.mean);
			if (e.velocity.size() == 0) continue;
			TBlock vel;
			vel.kind = BlockKind::ObjectVelocity;
			vel.dim = int(e.velocity.size());
			e.velocity_cov += gauge.term(&vel, e.velocity);
		}
	const TFilterView::TStateRef s = v.working();
	std::map<int32_t, std::vector<int>> velocityIdx;  // object-centric models (cv, ctrv, ca)
	for (size_t b = 0; b < s.layout.size(); ++b)
		if (s.layout[b].kind == BlockKind::ObjectVelocity)
			velocityIdx[s.layout[b].object] = s.layout.indices(b);
	for (size_t b = 0; b < s.layout.size(); ++b)
	{
		const TBlock& t = s.layout[b];
		if (t.kind != BlockKind::ObjectPose) continue;
		const std::vector<int> idx = s.layout.indices(b);
		TObjectPoseEstimate e;
		e.step = t.step;
		e.mean = s.x(idx);
		e.cov = ekf::marginal(s.P, idx) + gauge.term(&t, e.mean);
		// The velocity belongs to the newest pose: the only one of a velocity model in state.
		if (const auto vi = velocityIdx.find(t.object);
		    vi != velocityIdx.end() && t.step == v.step())
		{
			// The velocity: the block's first t.dim entries (ca: then its acceleration).
			const std::vector<int> iv(vi->second.begin(), vi->second.begin() + t.dim);
			e.velocity = s.x(iv);
			TBlock vel = t;
			vel.kind = BlockKind::ObjectVelocity;
			vel.dim = int(e.velocity.size());
			e.velocity_cov = ekf::marginal(s.P, iv) + gauge.term(&vel, e.velocity);
		}
		e.in_state = true;
		out[t.object].poses.push_back(e);
	}
	sortTrackPoses(out);
	return out;
}

size_t liveObjectCount(const TFilterView& v)
{
	std::vector<int32_t> objects;
	for (const TBlock& t : v.working().layout.blocks())
		if (t.kind == BlockKind::ObjectFeature0 || t.kind == BlockKind::ObjectFeatureT ||
		    t.kind == BlockKind::ObjectPose || t.kind == BlockKind::ObjectVelocity)
			objects.push_back(t.object);  // (a Compressed block's `object` is its level)
	std::sort(objects.begin(), objects.end());
	return size_t(std::unique(objects.begin(), objects.end()) - objects.begin());
}
}  // namespace dynslam::ekf::results
