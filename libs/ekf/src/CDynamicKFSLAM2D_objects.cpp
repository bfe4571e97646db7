/** CDynamicKFSLAM2D: the steps that add and drop state entries (Alg. 3 for new static landmarks
 * and object features, Alg. 4, the drop policies) and the object motion model (Alg. 6). A step
 * plans its augmentations on the state extended by the pending blocks (dynslam/core/ekf_steps.h,
 * "batched augmentation") and commits them with its drops in one rewrite of the covariance.
 * Where a block is stored is the typed layout's business (estimator::CPaddedLayout). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "modules/module_list.h"
#include "modules/object_motion.h"

namespace dynslam
{
using estimator::BlockKind;
using estimator::TBlock;

namespace
{
/** Where one object's blocks are, from one scan of the layout. */
struct TPoseBlocks
{
	int32_t object = -1;
	std::vector<std::pair<int32_t, size_t>> f0;  ///< (feature ID, its time-0 block), by ID
	std::vector<size_t> ft;                      ///< time-t feature blocks of the current step
	std::vector<size_t> poses;                   ///< pose blocks, ascending step
	/** The time-0 block of feature id (the last one if listed twice, as a map's assignment
	 * kept), or nullptr. */
	const size_t* findF0(int32_t id) const
	{
		auto it = std::upper_bound(f0.begin(), f0.end(), id,
		                           [](int32_t v, const auto& e) { return v < e.first; });
		return it != f0.begin() && (--it)->first == id ? &it->second : nullptr;
	}
};
/** The objects with a block, ascending ID (a range into a per-thread pool whose vectors keep
 * their capacity: the map of before allocated a node per object and per feature each step). */
struct TObjectIndex
{
	const TPoseBlocks *first, *last;
	const TPoseBlocks* begin() const { return first; }
	const TPoseBlocks* end() const { return last; }
};
bool indexed(BlockKind k, int blockStep, int step)
{
	return k == BlockKind::ObjectFeature0 || k == BlockKind::ObjectPose ||
	       (k == BlockKind::ObjectFeatureT && blockStep == step);
}
TObjectIndex indexObjects(const estimator::CPaddedLayout& L, int step)
{
	static thread_local std::vector<int32_t> objs;
	static thread_local std::vector<TPoseBlocks> pool;
	objs.clear();
	for (size_t b = 0; b < L.size(); ++b)
		if (indexed(L[b].kind, L[b].step, step)) objs.push_back(L[b].object);
	std::sort(objs.begin(), objs.end());
	objs.erase(std::unique(objs.begin(), objs.end()), objs.end());
	if (pool.size() < objs.size()) pool.resize(objs.size());
	for (size_t k = 0; k < objs.size(); ++k)
	{
		pool[k].object = objs[k];
		pool[k].f0.clear();
		pool[k].ft.clear();
		pool[k].poses.clear();
	}
	for (size_t b = 0; b < L.size(); ++b)
	{
		const TBlock& t = L[b];
		if (!indexed(t.kind, t.step, step)) continue;
		TPoseBlocks& o =
		    pool[size_t(std::lower_bound(objs.begin(), objs.end(), t.object) - objs.begin())];
		if (t.kind == BlockKind::ObjectFeature0)
			o.f0.emplace_back(t.id, b);
		else if (t.kind == BlockKind::ObjectFeatureT)
			o.ft.push_back(b);
		else
			o.poses.push_back(b);
	}
	for (size_t k = 0; k < objs.size(); ++k)
		std::stable_sort(pool[k].f0.begin(), pool[k].f0.end(),
		                 [](const auto& a, const auto& b) { return a.first < b.first; });
	return {pool.data(), pool.data() + objs.size()};
}

/** An object's pose fit at this step: its features with an f_0 block (founders first, in
 * feature-set order; only the founder for a one-founder object), the seen ones among them, and
 * the seen features without an f_0 yet (late joiners, doc/results/classification.md). */
struct TObjectFit
{
	std::vector<int> f0_idx, ft_idx, seen;
	std::vector<size_t> joiners;  ///< their time-t blocks
};
/** Writes the fit into `fit` (its vectors cleared first, their capacity kept). */
void objectFit(const estimator::CPaddedLayout& ext, const estimator::TObjectEntry& info,
               const TPoseBlocks& os, TObjectFit& fit)
{
	fit.f0_idx.clear();
	fit.ft_idx.clear();
	fit.seen.clear();
	fit.joiners.clear();
	static thread_local std::vector<std::pair<int32_t, int>> pos;  // feature ID -> column
	pos.clear();
	const auto findPos = [](int32_t id)
	{ return std::find_if(pos.begin(), pos.end(), [id](const auto& e) { return e.first == id; }); };
	for (const int32_t id : info.feature_ids)
	{
		const size_t* b0 = os.findF0(id);
		if (!b0 || (info.founders == 1 && !fit.f0_idx.empty())) continue;
		const auto it = findPos(id);
		if (it != pos.end())
			it->second = int(fit.f0_idx.size());
		else
			pos.emplace_back(id, int(fit.f0_idx.size()));
		fit.f0_idx.push_back(ext.first(*b0));
	}
	for (const size_t b : os.ft)
	{
		const auto it = findPos(ext[b].id);
		if (it != pos.end())
		{
			fit.ft_idx.push_back(ext.first(b));
			fit.seen.push_back(it->second);
		}
		else if (!os.findF0(ext[b].id))
			fit.joiners.push_back(b);
	}
}

/** ids sorted into out (a set's lookups by binary search, without its nodes). */
std::vector<int32_t>& sortedIds(const std::vector<int32_t>& ids, std::vector<int32_t>& out)
{
	out.assign(ids.begin(), ids.end());
	std::sort(out.begin(), out.end());
	return out;
}
bool contains(const std::vector<int32_t>& sorted, int32_t id)
{
	return std::binary_search(sorted.begin(), sorted.end(), id);
}

TBlock featureBlock(BlockKind kind, const estimator::TRoutedReading& m, int step)
{
	TBlock b;
	b.kind = kind;
	b.id = m.reading.id;
	b.object = m.object;
	b.feature = m.feature;
	b.step = step;
	b.dim = 2;
	return b;
}
}  // namespace

const estimator::CPaddedLayout& CDynamicKFSLAM2D::extendedLayout(const TPending& plan)
{
	m_ext = m_layout;  // copy assignment: reuses m_ext's capacity
	for (const auto& b : plan.blocks) m_ext.append(b);
	return m_ext;
}

void CDynamicKFSLAM2D::planFeatures(TPending& plan)
{
	using estimator::Route;
	std::vector<Eigen::Vector2d>& z = m_zScratch;
	z.clear();
	// Time-t features left from an earlier step (drop_time_t_features = false) are replaced
	// by this step's for the objects seen now.
	std::vector<int32_t>& seenObjects = m_idScratch;  // objects read now (unknown features too)
	seenObjects.clear();
	for (const auto& m : m_routed.readings)
		if (m.object >= 0) seenObjects.push_back(m.object);
	std::sort(seenObjects.begin(), seenObjects.end());
	for (size_t b = 0; b < m_layout.size(); ++b)
		if (m_layout[b].kind == BlockKind::ObjectFeatureT &&
		    contains(seenObjects, m_layout[b].object))
		{
			plan.remove.push_back(b);
			++m_report.dropped_time_t;
		}
	// New static landmarks first, then object features (time 0 of new objects, time t of
	// known ones), each in observation order (Alg. 3).
	for (const auto& m : m_routed.with(Route::StaticNew))
	{
		plan.blocks.push_back(featureBlock(BlockKind::StaticLandmark, m, m_step));
		z.push_back(m.reading.z);
		++m_report.static_new;
	}
	// Objects with a velocity (object-centric models) were updated by their readings.
	const ekf::CObjectMotionModule* motion = m_modules->objectMotion();
	const std::set<int32_t> withState =
	    motion ? motion->objectsWithVelocity(m_layout) : std::set<int32_t>();
	for (const auto& m : m_routed.objects())
	{
		if (withState.count(m.object)) continue;
		const bool first = m.route == Route::ObjectFirstSighting;
		plan.blocks.push_back(
		    featureBlock(first ? BlockKind::ObjectFeature0 : BlockKind::ObjectFeatureT, m, m_step));
		z.push_back(m.reading.z);
		++(first ? m_report.object_features_new : m_report.object_features_t);
	}
	if (z.empty()) return;
	plan.a = ekf::featureAugmentation(options.measurement_model,
	                                  Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]),
	                                  cov().topRows(3), z, options.Sigma_v, m_in.sensor_pose);
}

void CDynamicKFSLAM2D::planObjectPoses(TPending& plan)
{
	// Layout and mean of the state extended by the pending features.
	const estimator::CPaddedLayout& ext = extendedLayout(plan);
	const Eigen::Index n = m_xkk.size();
	m_xScratch.resize(size_t(n + plan.a.mean.size()));
	Eigen::Map<Eigen::VectorXd> x(m_xScratch.data(), n + plan.a.mean.size());
	x << m_xkk.asEigen(), plan.a.mean;

	static thread_local std::vector<ekf::ObjectPoseLinearization> lins;
	static thread_local std::vector<TBlock> poses;
	static thread_local std::vector<Eigen::Index> at;  // first entry of each pose among the new
	static thread_local TObjectFit fit;
	lins.clear();
	poses.clear();
	at.clear();
	Eigen::Index size = 0;
	for (const TPoseBlocks& os : indexObjects(ext, m_step))
	{
		const int32_t obj = os.object;
		if (os.ft.empty()) continue;
		const estimator::TObjectEntry& info = m_router->registry().at(obj);
		objectFit(ext, info, os, fit);
		if (fit.f0_idx.empty() || (info.founders >= 2 && fit.ft_idx.size() < 2) ||
		    (info.founders == 1 && fit.ft_idx.size() != 1))
		{
			++m_report.skipped_pose_degenerate;  // rotation undetermined from one feature
			continue;
		}
		try
		{
			lins.push_back(ekf::linearizeObjectPose(x, fit.f0_idx, fit.ft_idx, fit.seen,
			                                        options.Sigma_xi, info.founders));
		}
		catch (const std::domain_error& e)
		{
			// Documented skip: coinciding features leave the rotation undetermined.
			++m_report.skipped_pose_degenerate;
			MRPT_LOG_WARN_STREAM("object " << obj << " step " << m_step << ": " << e.what());
			continue;
		}
		TBlock p;
		p.kind = BlockKind::ObjectPose;
		p.object = obj;
		p.step = m_step;
		p.dim = int(lins.back().xi.size());
		at.push_back(size);
		poses.push_back(p);
		++m_report.object_poses_added;
		if (!fit.joiners.empty())
		{
			// Late joiners: their f_0 from this step's pose and reading, right after the pose.
			std::vector<int> ft;
			for (const size_t b : fit.joiners)
			{
				ft.push_back(ext.first(b));
				TBlock f = ext[b];
				f.kind = BlockKind::ObjectFeature0;
				poses.push_back(f);
				++m_report.object_features_joined;
			}
			lins.back() =
			    ekf::appendJoinedFeatures(x, lins.back(), info.founders, ft, 2 * p.slots());
		}
		size += 2 * p.slots() + 2 * Eigen::Index(fit.joiners.size());
	}
	if (lins.empty()) return;
	plan.b = ekf::objectPoseAugmentations(cov(), plan.a, lins, at, size);
	plan.blocks.insert(plan.blocks.end(), poses.begin(), poses.end());
}

void CDynamicKFSLAM2D::applyObjectMotion()
{
	for (const TPoseBlocks& os : indexObjects(m_layout, m_step))
	{
		const int32_t obj = os.object;
		const int d = m_router->registry().at(obj).poseDim();
		std::vector<int> steps;
		for (const size_t b : os.poses) steps.push_back(m_layout[b].step);
		for (const auto& pm : m_motion->select(obj, m_step, steps, d))
		{
			std::vector<int> base;
			for (const int st : pm.steps)
			{
				const auto it = std::find(steps.begin(), steps.end(), st);
				base.push_back(m_layout.first(os.poses[size_t(it - steps.begin())]));
			}
			auto x = m_xkk.asEigen();
			auto P = cov();
			ekf::pseudoMeasurementUpdate(
			    x, P, base, d,
			    [&](const std::vector<Eigen::VectorXd>& v, std::vector<Eigen::MatrixXd>* J)
			    { return m_motion->residual(pm, v, J); },
			    pm.R);
			++m_report.smoothing_updates;
		}
	}
}

void CDynamicKFSLAM2D::planDrops(TPending& plan)
{
	// Over the blocks extended by the pending ones; only existing entries can be old enough to
	// be recorded (a pending pose is the newest of its object, K >= 1), so marginals come from P.
	const estimator::CPaddedLayout& ext = extendedLayout(plan);
	std::vector<size_t>& remove = plan.remove;
	const auto P = cov();
	// Time-t features, once they have served the pose augmentation (stale ones from earlier
	// steps may already be listed by planFeatures).
	if (m_drop.dropTimeT())
	{
		std::vector<bool>& listed = m_dropFlags;
		listed.assign(ext.size(), false);
		for (const size_t b : remove) listed[b] = true;
		for (size_t b = 0; b < ext.size(); ++b)
			if (ext[b].kind == BlockKind::ObjectFeatureT && !listed[b])
			{
				remove.push_back(b);
				++m_report.dropped_time_t;
			}
	}
	// Object poses beyond the last K: recorded with their marginal covariance.
	for (const TPoseBlocks& os : indexObjects(ext, m_step))
	{
		const int32_t obj = os.object;
		const size_t nd = m_drop.posesToDrop(os.poses.size());
		for (size_t i = 0; i < nd; ++i)
		{
			const size_t b = os.poses[i];
			if (b >= m_layout.size())
				throw std::logic_error("CDynamicKFSLAM2D: a pose added in this step is dropped");
			const std::vector<int> idx = m_layout.indices(b);
			estimator::TPoseRecord e;
			e.step = m_layout[b].step;
			e.dim = int(idx.size());
			for (int r = 0; r < e.dim; ++r)
			{
				e.mean[r] = m_xkk[idx[r]];
				for (int c = 0; c < e.dim; ++c) e.cov(r, c) = P(idx[r], idx[c]);
			}
			m_router->registry().recordDroppedPose(obj, e, m_drop.record());
			remove.push_back(b);
			++m_report.dropped_poses;
		}
	}
	// Static landmarks unseen for too long or pruned (optional; never one added in this step),
	// and those the router reclassified as moving (feature_labels = classify: not recorded as
	// static).
	std::vector<int32_t>& moving = sortedIds(m_routed.reclassified, m_idScratch);
	std::vector<int32_t>& candidates = sortedIds(m_routed.dropped_candidates, m_idScratch2);
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const TBlock& t = m_layout[b];
		if (t.kind != BlockKind::StaticLandmark) continue;
		const bool isMoving = contains(moving, t.id);
		if (isMoving || contains(candidates, t.id))
		{
			forgetStatic(t.id);
			remove.push_back(b);
			++(isMoving ? m_report.reclassified_static : m_report.dropped_candidates);
			continue;
		}
		const bool unseen = m_drop.staticDue(t.id, m_step, t.step);
		if (!unseen && !m_drop.pruneDue(t.id, m_step, t.step)) continue;
		const std::vector<int> idx = m_layout.indices(b);
		TStaticLandmarkEstimate e;
		e.id = t.id;
		e.mean = Eigen::Vector2d(m_xkk[idx[0]], m_xkk[idx[1]]);
		e.cov = ekf::marginal(P, idx);
		e.in_state = false;
		if (m_drop.record()) m_droppedStatic.push_back(e);
		forgetStatic(t.id);  // only landmarks in the state are tracked
		remove.push_back(b);
		++(unseen ? m_report.dropped_static : m_report.pruned_static);
	}
}

void CDynamicKFSLAM2D::commit(TPending& plan)
{
	const Eigen::Index n = m_xkk.size(), ma = plan.a.mean.size(), mb = plan.b.mean.size(),
	                   m = ma + mb;
	if (m == 0 && plan.remove.empty()) return;
	extendedLayout(plan);
	estimator::CPaddedLayout& ext = m_ext;
	if (ext.storageDim() != n + m)
		throw std::logic_error("CDynamicKFSLAM2D::commit: inconsistent block sizes");
	if (ma == 0) plan.a.cross.resize(0, n);
	std::vector<bool>& drop = m_dropFlags;
	drop.assign(ext.size(), false);
	for (const size_t b : plan.remove)
	{
		if (b >= ext.size()) throw std::out_of_range("CDynamicKFSLAM2D::commit: block index");
		drop[b] = true;
	}
	const std::vector<int> keep = ext.keptStorage(drop);
	const Eigen::Index N = Eigen::Index(keep.size());

	// The new covariance is written in place (doc/results/performance.md, section 10): the kept old
	// entries move towards the top-left corner (not at all if nothing old is dropped), the new
	// ones are written after them. Only a state that outgrows the buffer's side is copied into
	// a larger buffer.
	if (m_cov.keeps(N))
	{
		ekf::assembleInPlace(m_cov.data(), m_cov.stride(), n, plan.a, plan.b, keep);
		m_cov.resize(N);
	}
	else
	{
		ekf::CSquareBuffer next;
		next.resize(N);
		ekf::assembleExtended(m_cov.view(), plan.a, plan.b, keep, next.view());
		m_cov.swap(next);
	}
	m_pkkStale = true;
	m_xScratch.resize(size_t(n + m));
	Eigen::Map<Eigen::VectorXd> x(m_xScratch.data(), n + m);
	x << m_xkk.asEigen(), plan.a.mean, plan.b.mean;
	m_xkk.resize(size_t(N));
	for (Eigen::Index i = 0; i < N; ++i) m_xkk[i] = x[keep[size_t(i)]];

	ext.removeBlocks(drop);
	std::swap(m_layout, m_ext);  // both keep their capacity
	onLayoutChanged();
	plan.a = plan.b = ekf::Augmentation();
	plan.blocks.clear();
	plan.remove.clear();
}

}  // namespace dynslam
