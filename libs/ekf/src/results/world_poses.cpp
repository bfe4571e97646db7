/** Results: an object's pose in the world (issue 30 item 5; object_world_estimate.h,
 * models/object_world_pose.h; reader.h). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/object_world_pose.h>

#include <stdexcept>
#include <string>

#include "../gauge/prior_gauge.h"
#include "../index_append.h"
#include "reader.h"
#include "world_blocks.h"

namespace dynslam::ekf
{
using estimator::BlockKind;
using estimator::TBlock;

TWorldBlocks worldBlocksOf(const estimator::CPaddedLayout& L, int32_t obj)
{
	TWorldBlocks o;
	for (size_t b = 0; b < L.size(); ++b)
	{
		const TBlock& t = L[b];
		if (t.object != obj) continue;
		if (t.kind == BlockKind::ObjectPose && (o.pose == SIZE_MAX || L[o.pose].step <= t.step))
			o.pose = b;
		else if (t.kind == BlockKind::ObjectVelocity)
			o.vel = b;
		else if (t.kind == BlockKind::ObjectFeature0)
			o.f0[t.id] = b;
	}
	return o;
}

const estimator::TObjectEntry& entryOf(const estimator::CObjectRegistry& reg, int32_t obj,
                                       const char* who)
{
	if (!reg.has(obj))
		throw std::invalid_argument(std::string("CDynamicKFSLAM2D::") + who + ": object " +
		                            std::to_string(obj) + " is not known to the filter");
	return reg.at(obj);
}

namespace results
{
std::optional<TObjectWorldPose> objectWorldPose(const TFilterView& v, int32_t object)
{
	const estimator::TObjectEntry& e = entryOf(v.objects(), object, "getObjectWorldPose");
	if (e.dropped) return std::nullopt;  // drop_object_after_unseen_steps
	const TFilterView::TStateRef s = v.whole();
	const TWorldBlocks o = worldBlocksOf(s.layout, object);
	const int d = e.poseDim();
	// Inputs [xi; founders' f_0]; without a pose in the state, only before any pose was made
	// (the first sighting: xi = 0 exactly, no entries).
	std::vector<int> idx;
	TObjectWorldPose w;
	w.object = object;
	if (o.pose != SIZE_MAX)
	{
		if (s.layout[o.pose].dim != d) return std::nullopt;  // not the founders' pose (merged)
		idx = s.layout.indices(o.pose);
		w.step = s.layout[o.pose].step;
	}
	else if (e.dropped_poses.empty() && e.first_step >= 0)
		w.step = e.first_step;
	else
		return std::nullopt;
	if (e.founders < 1) return std::nullopt;
	Eigen::Matrix2Xd f0(2, e.founders);
	for (int k = 0; k < e.founders; ++k)
	{
		const auto it = o.f0.find(e.feature_ids[size_t(k)]);
		if (it == o.f0.end()) return std::nullopt;
		const std::vector<int> fi = s.layout.indices(it->second);
		f0.col(k) = s.x(fi);
		ekf::appendIndices(idx, fi);
	}
	const Eigen::VectorXd xi =
	    o.pose != SIZE_MAX ? s.x(idx).head(d).eval() : Eigen::VectorXd::Zero(d).eval();
	Eigen::MatrixXd J_w_in;
	w.mean = models::objectWorldPose(xi, f0, &J_w_in);
	if (o.pose == SIZE_MAX) J_w_in = J_w_in.rightCols(2 * e.founders).eval();
	Eigen::MatrixXd P_in = ekf::marginal(s.P, idx);
	if (v.gauge().anchored())  // the output term of the inputs, cross terms included
	{
		const Eigen::MatrixXd N = gaugeJacobian(v)(idx, Eigen::all);
		P_in += N * v.options().Sigma_0 * N.transpose();
	}
	w.cov = J_w_in * P_in * J_w_in.transpose();
	w.velocity = v.f.getObjectVelocity(object);
	return w;
}

std::map<int32_t, TObjectWorldPose> objectWorldPoses(const TFilterView& v)
{
	std::map<int32_t, TObjectWorldPose> out;
	for (const auto& [obj, e] : v.objects().objects())
		if (auto w = objectWorldPose(v, obj)) out.emplace(obj, std::move(*w));
	return out;
}
}  // namespace results
}  // namespace dynslam::ekf
