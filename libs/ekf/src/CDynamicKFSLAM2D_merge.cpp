/** CDynamicKFSLAM2D: merging an object that reappears under new IDs into the lost object it was
 * linked to (classify_merge_linked with an object-centric model, doc/results/classification.md
 * "Merging a linked object"): a state surgery x' = g(x), P' = J P J^T (models/object_merge.h). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/object_merge.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/state_helper.h>

#include <stdexcept>
#include <string>

#include "index_append.h"
#include "modules/module_list.h"

namespace dynslam
{
using estimator::BlockKind;

namespace
{
/** The blocks of one object: its newest pose, velocity, f_0 by feature ID and the rest. */
struct TObjectBlocks
{
	size_t pose = SIZE_MAX, velocity = SIZE_MAX;
	std::map<int32_t, size_t> f0;
	std::vector<size_t> poses, featuresT;
};

TObjectBlocks blocksOf(const estimator::CPaddedLayout& L, int32_t obj)
{
	TObjectBlocks o;
	for (size_t b = 0; b < L.size(); ++b)
	{
		const estimator::TBlock& t = L[b];
		if (t.object != obj) continue;
		if (t.kind == BlockKind::ObjectPose)
		{
			o.poses.push_back(b);
			if (o.pose == SIZE_MAX || L[o.pose].step <= t.step) o.pose = b;
		}
		else if (t.kind == BlockKind::ObjectVelocity)
			o.velocity = b;
		else if (t.kind == BlockKind::ObjectFeature0)
			o.f0[t.id] = b;
		else if (t.kind == BlockKind::ObjectFeatureT)
			o.featuresT.push_back(b);
	}
	return o;
}

}  // namespace

bool CDynamicKFSLAM2D::mergeObjects(int32_t from, int32_t into)
{
	const estimator::CObjectRegistry& reg = m_router->registry();
	if (from == into || !reg.has(from) || !reg.has(into))
		throw std::logic_error("CDynamicKFSLAM2D::mergeObjects: cannot merge object " +
		                       std::to_string(from) + " into " + std::to_string(into));
	const TObjectBlocks L = blocksOf(m_layout, into), N = blocksOf(m_layout, from);
	if (L.pose == SIZE_MAX) return false;
	if (m_motion->objectCentric())
	{
		// Without a velocity the lost object was not predicted across the gap: nothing to merge
		// into.
		if (L.velocity == SIZE_MAX) return false;
	}
	// The paper's model (classify_merge_live): both poses of this step (N's f_0 are in N's
	// first-sighting frame, brought to now by xi_N,t).
	else if (N.pose == SIZE_MAX || m_layout[L.pose].step != m_step ||
	         m_layout[N.pose].step != m_step)
		return false;
	const estimator::TObjectEntry eL = reg.at(into), eN = reg.at(from);
	// The input entries of g: [xi_L; L's founders' f_0 (3-dof pose); xi_N; N's f_0].
	std::vector<int> in = m_layout.indices(L.pose);
	const int dL = int(in.size());
	if (dL == 3)
		for (int k = 0; k < eL.founders; ++k)
			ekf::appendIndices(in, m_layout.indices(L.f0.at(eL.feature_ids[size_t(k)])));
	const int nL = dL == 3 ? eL.founders : 0;
	const std::vector<int> ipN = N.pose == SIZE_MAX ? std::vector<int>{} : m_layout.indices(N.pose);
	ekf::appendIndices(in, ipN);
	const Eigen::Index off = Eigen::Index(in.size());  // first entry of N's features
	for (const int32_t id : eN.feature_ids)
	{
		const auto b = N.f0.find(id);
		if (b == N.f0.end())
			throw std::logic_error("CDynamicKFSLAM2D::mergeObjects: feature " + std::to_string(id) +
			                       " of object " + std::to_string(from) + " has no f_0");
		ekf::appendIndices(in, m_layout.indices(b->second));
	}
	auto x = m_xkk.asEigen();
	const Eigen::VectorXd xin = x(in);
	const Eigen::Index m = Eigen::Index(eN.feature_ids.size());
	Eigen::Matrix2Xd f0L(2, nL), fN(2, m);
	for (int k = 0; k < nL; ++k) f0L.col(k) = xin.segment(dL + 2 * k, 2);
	for (Eigen::Index k = 0; k < m; ++k) fN.col(k) = xin.segment(off + 2 * k, 2);
	Eigen::MatrixXd J;
	const Eigen::Matrix2Xd f = models::mergeObjectFeatures(
	    xin.head(dL), f0L, xin.segment(dL + 2 * nL, Eigen::Index(ipN.size())), fN, eN.founders, &J);
	// The router moves N's tracks to L (N leaves the registry) before the state changes: a
	// router that cannot merge throws with the filter unchanged. The f_0 blocks follow below.
	m_router->mergeObjects(from, into);
	// x' = g(x): identity outside N's features, whose rows are J (P' = J P J^T).
	const std::vector<int> out(in.begin() + off, in.end());
	const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(f.data(), 2 * m);
	auto P = cov();
	estimator::state::replace(x, P, in, out, g, J);
	const estimator::TObjectEntry& eM = m_router->registry().at(into);
	for (const int32_t id : eN.feature_ids)
		m_layout.reassignObjectFeature0(N.f0.at(id), into,
		                                eM.feature_index[size_t(eM.indexOf(id))]);
	TPending plan;
	plan.remove = N.poses;
	plan.remove.insert(plan.remove.end(), N.featuresT.begin(), N.featuresT.end());
	if (N.velocity != SIZE_MAX) plan.remove.push_back(N.velocity);
	commit(plan);  // N's pose, velocity and time-t features leave the state (marginalised)
	onLayoutChanged();
	m_modules->objectForgotten(from);  // object motion: from is no longer awaiting a velocity
	return true;
}
}  // namespace dynslam
