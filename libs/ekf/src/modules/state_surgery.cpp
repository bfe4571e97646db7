/** The state surgeries of classification (state_surgery.h): a static landmark becomes an object
 * feature; an object that reappears under new IDs (or a live object found rigid with another)
 * merges into the other, a surgery x' = g(x), P' = J P J^T (models/object_merge.h). */
#include "state_surgery.h"

#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/object_merge.h>
#include <dynslam/estimator/state_helper.h>

#include <set>
#include <stdexcept>
#include <string>

#include "../index_append.h"

namespace dynslam::ekf
{
using estimator::BlockKind;

void convertStaticLandmarks(TFilterAccess& a,
                            const std::vector<estimator::TRoutedStep::TConversion>& conversions)
{
	if (conversions.empty()) return;
	std::set<int32_t> ids;  // checked first: a bad list changes nothing
	for (const auto& c : conversions)
		if (!a.staticBlocks().count(c.id) || !ids.insert(c.id).second)
			throw std::logic_error("CDynamicKFSLAM2D: state surgery: landmark " +
			                       std::to_string(c.id) +
			                       " is not a static landmark in the state (or listed twice)");
	for (const auto& c : conversions)
	{
		a.editLayout().convertToObjectFeature0(a.staticBlocks().at(c.id), c.object, c.feature);
		a.forgetStatic(c.id);
		++a.report().converted_static;
	}
	a.layoutChanged();
}

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

/** Whether the objects' blocks allow the merge (mergeObjects' conditions). */
bool mergeable(TFilterAccess& a, const TObjectBlocks& L, const TObjectBlocks& N)
{
	if (L.pose == SIZE_MAX) return false;
	// Without a velocity the lost object was not predicted across the gap: nothing to merge into.
	if (a.motion().objectCentric()) return L.velocity != SIZE_MAX;
	// The paper's model (classify_merge_live): both poses of this step (N's f_0 are in N's
	// first-sighting frame, brought to now by xi_N,t).
	return N.pose != SIZE_MAX && a.layout()[L.pose].step == a.step() &&
	       a.layout()[N.pose].step == a.step();
}

/** The input entries of g, [xi_L; L's founders' f_0 (3-dof pose); xi_N; N's f_0]: their
 * indices, the size of xi_L, the founders of L used, the size of xi_N, where N's f_0 start. */
struct TMergeInput
{
	std::vector<int> in;
	int dL = 0, nL = 0, dN = 0;
	Eigen::Index off = 0;  ///< the first entry of N's features in `in`
};

TMergeInput mergeInput(const estimator::CPaddedLayout& layout, const TObjectBlocks& L,
                       const TObjectBlocks& N, const estimator::TObjectEntry& eL,
                       const estimator::TObjectEntry& eN, int32_t from)
{
	TMergeInput g;
	g.in = layout.indices(L.pose);
	g.dL = int(g.in.size());
	if (g.dL == 3)
		for (int k = 0; k < eL.founders; ++k)
			ekf::appendIndices(g.in, layout.indices(L.f0.at(eL.feature_ids[size_t(k)])));
	g.nL = g.dL == 3 ? eL.founders : 0;
	const std::vector<int> ipN = N.pose == SIZE_MAX ? std::vector<int>{} : layout.indices(N.pose);
	g.dN = int(ipN.size());
	ekf::appendIndices(g.in, ipN);
	g.off = Eigen::Index(g.in.size());
	for (const int32_t id : eN.feature_ids)
	{
		const auto b = N.f0.find(id);
		if (b == N.f0.end())
			throw std::logic_error("CDynamicKFSLAM2D::mergeObjects: feature " + std::to_string(id) +
			                       " of object " + std::to_string(from) + " has no f_0");
		ekf::appendIndices(g.in, layout.indices(b->second));
	}
	return g;
}
}  // namespace

bool mergeObjects(TFilterAccess& a, int32_t from, int32_t into)
{
	const estimator::CObjectRegistry& reg = a.router().registry();
	if (from == into || !reg.has(from) || !reg.has(into))
		throw std::logic_error("CDynamicKFSLAM2D::mergeObjects: cannot merge object " +
		                       std::to_string(from) + " into " + std::to_string(into));
	const TObjectBlocks L = blocksOf(a.layout(), into), N = blocksOf(a.layout(), from);
	if (!mergeable(a, L, N)) return false;
	const estimator::TObjectEntry eL = reg.at(into), eN = reg.at(from);
	const TMergeInput g = mergeInput(a.layout(), L, N, eL, eN, from);
	const std::vector<int>& in = g.in;
	const Eigen::Index off = g.off;
	auto x = a.mean();
	const Eigen::VectorXd xin = x(in);
	const Eigen::Index m = Eigen::Index(eN.feature_ids.size());
	Eigen::Matrix2Xd f0L(2, g.nL), fN(2, m);
	for (int k = 0; k < g.nL; ++k) f0L.col(k) = xin.segment(g.dL + 2 * k, 2);
	for (Eigen::Index k = 0; k < m; ++k) fN.col(k) = xin.segment(off + 2 * k, 2);
	Eigen::MatrixXd J;
	const Eigen::Matrix2Xd f = models::mergeObjectFeatures(
	    xin.head(g.dL), f0L, xin.segment(g.dL + 2 * g.nL, g.dN), fN, eN.founders, &J);
	// The router moves N's tracks to L (N leaves the registry) before the state changes: a
	// router that cannot merge throws with the filter unchanged. The f_0 blocks follow below.
	a.router().mergeObjects(from, into);
	// x' = g(x): identity outside N's features, whose rows are J (P' = J P J^T).
	const std::vector<int> out(in.begin() + off, in.end());
	const Eigen::VectorXd gx = Eigen::Map<const Eigen::VectorXd>(f.data(), 2 * m);
	auto P = a.cov();
	estimator::state::replace(x, P, in, out, gx, J);
	const estimator::TObjectEntry& eM = a.router().registry().at(into);
	for (const int32_t id : eN.feature_ids)
		a.editLayout().reassignObjectFeature0(N.f0.at(id), into,
		                                      eM.feature_index[size_t(eM.indexOf(id))]);
	TFilterAccess::TPending plan;
	plan.remove = N.poses;
	plan.remove.insert(plan.remove.end(), N.featuresT.begin(), N.featuresT.end());
	if (N.velocity != SIZE_MAX) plan.remove.push_back(N.velocity);
	a.commit(plan);  // N's pose, velocity and time-t features leave the state (marginalised)
	a.layoutChanged();
	a.objectForgotten(from);  // object motion: from's per-step sets
	return true;
}
}  // namespace dynslam::ekf
