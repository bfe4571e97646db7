/** The object-drop module (object_drop.h). */
#include "object_drop.h"

#include <stdexcept>
#include <type_traits>

namespace dynslam::ekf
{
using estimator::BlockKind;
using estimator::TBlock;

namespace
{
bool isObjectBlock(BlockKind k)
{
	return k == BlockKind::ObjectFeature0 || k == BlockKind::ObjectFeatureT ||
	       k == BlockKind::ObjectPose || k == BlockKind::ObjectVelocity;
}

/** Mean and marginal covariance of the first `dim` entries of idx (a pose or a velocity). */
template <class Record, class Vec, class Mat>
Record recordOf(const Vec& x, const Mat& P, const std::vector<int>& idx, int step, int dim)
{
	Record e;
	e.step = step;
	e.dim = dim;
	for (int r = 0; r < dim; ++r)
		for (int c = 0; c < dim; ++c) e.cov(r, c) = P(idx[size_t(r)], idx[size_t(c)]);
	for (int r = 0; r < dim; ++r)
	{
		if constexpr (std::is_same_v<Record, estimator::TPoseRecord>)
			e.mean[r] = x[idx[size_t(r)]];
		else
			e.velocity[r] = x[idx[size_t(r)]];
	}
	return e;
}
}  // namespace

std::unique_ptr<CObjectDropModule> makeObjectDropModule(TFilterAccess& a)
{
	if (a.dropPolicy().options().drop_object_after_unseen_steps <= 0) return nullptr;
	return std::make_unique<CObjectDropModule>();
}

void CObjectDropModule::planDrops(TFilterAccess& a, TPending& plan)
{
	estimator::CDropPolicy& drop = a.dropPolicy();
	estimator::CObjectRegistry& registry = a.router().registry();
	const int step = a.step();
	std::vector<int32_t> due;
	for (const auto& [obj, entry] : registry.objects())
		if (!entry.dropped && drop.objectDue(obj, step, entry.first_step)) due.push_back(obj);
	if (due.empty()) return;
	const estimator::CPaddedLayout& ext = a.extendedLayout(plan);
	const estimator::CPaddedLayout& layout = a.layout();
	std::vector<bool>& listed = m_listed;
	listed.assign(ext.size(), false);
	for (const size_t b : plan.remove) listed[b] = true;
	const auto P = a.cov();
	const auto x = a.mean();
	for (const int32_t obj : due)
	{
		size_t velocity = SIZE_MAX, newest = SIZE_MAX;
		for (size_t b = 0; b < ext.size(); ++b)
		{
			const TBlock& t = ext[b];
			if (t.object != obj || !isObjectBlock(t.kind)) continue;
			if (b >= layout.size())
				throw std::logic_error("CDynamicKFSLAM2D: an object without readings got a block");
			if (t.kind == BlockKind::ObjectVelocity) velocity = b;
			if (t.kind == BlockKind::ObjectPose &&
			    (newest == SIZE_MAX || t.step > ext[newest].step))
				newest = b;
		}
		for (size_t b = 0; b < ext.size(); ++b)
		{
			const TBlock& t = ext[b];
			if (t.object != obj || !isObjectBlock(t.kind) || listed[b]) continue;
			const std::vector<int> idx = layout.indices(b);
			if (t.kind == BlockKind::ObjectPose)
			{
				const int dim = int(idx.size());
				registry.recordDroppedPose(
				    obj, recordOf<estimator::TPoseRecord>(x, P, idx, t.step, dim), drop.record());
				if (b == newest && velocity != SIZE_MAX)  // the velocity: its first dim entries
					registry.recordDroppedVelocity(obj,
					                               recordOf<estimator::TVelocityRecord>(
					                                   x, P, layout.indices(velocity), t.step, dim),
					                               drop.record());
			}
			else if (t.kind == BlockKind::ObjectFeature0 && drop.record())
			{
				TObjectFeatureEstimate f;
				f.object = obj;
				f.feature = t.feature;
				f.id = t.id;
				f.at_time0 = true;
				f.step = t.step;
				f.mean = Eigen::Vector2d(x[idx[0]], x[idx[1]]);
				f.cov << P(idx[0], idx[0]), P(idx[0], idx[1]), P(idx[1], idx[0]), P(idx[1], idx[1]);
				m_dropped.push_back(f);
			}
			plan.remove.push_back(b);
			listed[b] = true;
		}
		registry.markDropped(obj);
		drop.forgetObject(obj);
		a.objectForgotten(obj);  // object motion: its per-step sets
		++a.report().dropped_objects;
	}
}
}  // namespace dynslam::ekf
