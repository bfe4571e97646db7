/** CDynamicKFSLAM2D: the steps that add and drop state entries (Alg. 3 for new static landmarks
 * and object features, Alg. 4, the drop policies) and Alg. 6. A step plans its augmentations
 * on the state extended by the pending entries (dynslam/ekf_steps.h, "batched augmentation")
 * and commits them with its drops in one rewrite of the covariance. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/ekf_steps.h>
#include <dynslam/landmark_ids.h>

#include <algorithm>
#include <set>
#include <stdexcept>

namespace dynslam
{
namespace
{
/** Where each object's slots are, from one scan of the slot table. */
struct TObjectSlots
{
	std::map<int32_t, size_t> f0;  ///< feature ID -> slot
	std::vector<size_t> ft;        ///< time-t feature slots of the current step
	std::vector<size_t> poseA;     ///< pose part-A slots, ascending step
};
std::map<int32_t, TObjectSlots> indexObjects(const std::vector<TSlot>& slots, int step)
{
	std::map<int32_t, TObjectSlots> out;
	for (size_t s = 0; s < slots.size(); ++s)
	{
		const TSlot& t = slots[s];
		switch (t.kind)
		{
			case SlotKind::ObjectFeature0:
				out[t.object].f0[t.id] = s;
				break;
			case SlotKind::ObjectFeatureT:
				if (t.step == step) out[t.object].ft.push_back(s);
				break;
			case SlotKind::ObjectPoseA:
				out[t.object].poseA.push_back(s);
				break;
			default:
				break;
		}
	}
	return out;
}
}  // namespace

std::vector<TSlot> CDynamicKFSLAM2D::extendedSlots(const TPending& plan) const
{
	std::vector<TSlot> ext;
	ext.reserve(m_slots.size() + plan.slots.size());
	ext.insert(ext.end(), m_slots.begin(), m_slots.end());
	ext.insert(ext.end(), plan.slots.begin(), plan.slots.end());
	return ext;
}

void CDynamicKFSLAM2D::planFeatures(TPending& plan)
{
	using estimator::Route;
	std::vector<Eigen::Vector2d> z;
	std::vector<TSlot> slots;
	// Time-t features left from an earlier step (drop_time_t_features = false) are replaced
	// by this step's for the objects seen now.
	std::set<int32_t> seenObjects;  // objects read now (unknown features included)
	for (const auto& m : m_routed.readings)
		if (m.object >= 0) seenObjects.insert(m.object);
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (m_slots[s].kind == SlotKind::ObjectFeatureT && seenObjects.count(m_slots[s].object))
		{
			plan.remove.push_back(s);
			++m_report.dropped_time_t;
		}
	// New static landmarks first, then object features (time 0 of new objects, time t of
	// known ones), each in observation order (Alg. 3).
	for (const auto& m : m_routed.with(Route::StaticNew))
	{
		TSlot s;
		s.kind = SlotKind::StaticLandmark;
		s.id = m.reading.id;
		s.step = m_step;
		z.push_back(m.reading.z);
		slots.push_back(s);
		++m_report.static_new;
	}
	for (const auto& m : m_routed.objects())
	{
		TSlot s;
		s.id = m.reading.id;
		s.object = m.object;
		s.feature = m.feature;
		s.step = m_step;
		const bool first = m.route == Route::ObjectFirstSighting;
		s.kind = first ? SlotKind::ObjectFeature0 : SlotKind::ObjectFeatureT;
		++(first ? m_report.object_features_new : m_report.object_features_t);
		z.push_back(m.reading.z);
		slots.push_back(s);
	}
	if (z.empty()) return;
	plan.a = ekf::featureAugmentation(options.measurement_model,
	                                  Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]),
	                                  m_pkk.asEigen().topRows(3), z, options.Sigma_v);
	plan.slots = std::move(slots);
}

void CDynamicKFSLAM2D::planObjectPoses(TPending& plan)
{
	// Slots and mean of the state extended by the pending features.
	const std::vector<TSlot> ext = extendedSlots(plan);
	const Eigen::Index n = m_xkk.size();
	Eigen::VectorXd x(n + plan.a.mean.size());
	x << m_xkk.asEigen(), plan.a.mean;

	std::vector<ekf::ObjectPoseLinearization> lins;
	std::vector<TSlot> slots;
	std::vector<Eigen::Index> at;  // first entry of each pose among the new entries
	for (const auto& [obj, os] : indexObjects(ext, m_step))
	{
		if (os.ft.empty()) continue;
		const estimator::TObjectEntry& info = m_router->registry().at(obj);
		const int nf = int(info.feature_ids.size()), m = int(os.ft.size());
		if (nf >= 2 && m < 2)
		{
			++m_report.skipped_pose_degenerate;  // rotation undetermined from one feature
			continue;
		}
		std::vector<int> f0_idx, ft_idx, seen;
		for (const int32_t id : info.feature_ids)
			f0_idx.push_back(int(slotStateIndex(os.f0.at(id))));
		for (const size_t s : os.ft)
		{
			ft_idx.push_back(int(slotStateIndex(s)));
			const auto pos = std::find(info.feature_ids.begin(), info.feature_ids.end(), ext[s].id);
			seen.push_back(int(pos - info.feature_ids.begin()));
		}
		try
		{
			lins.push_back(ekf::linearizeObjectPose(x, f0_idx, ft_idx, seen, options.Sigma_xi));
		}
		catch (const std::domain_error& e)
		{
			// Documented skip: coinciding features leave the rotation undetermined.
			++m_report.skipped_pose_degenerate;
			MRPT_LOG_WARN_STREAM("object " << obj << " step " << m_step << ": " << e.what());
			continue;
		}
		TSlot sa;
		sa.kind = SlotKind::ObjectPoseA;
		sa.object = obj;
		sa.step = m_step;
		at.push_back(Eigen::Index(2 * slots.size()));
		slots.push_back(sa);
		if (lins.back().xi.size() == 3)
		{
			TSlot sb = sa;  // [dtheta, pad]
			sb.kind = SlotKind::ObjectPoseB;
			slots.push_back(sb);
		}
		++m_report.object_poses_added;
	}
	if (lins.empty()) return;
	plan.b = ekf::objectPoseAugmentations(m_pkk.asEigen(), plan.a, lins, at,
	                                      Eigen::Index(2 * slots.size()));
	plan.slots.insert(plan.slots.end(), slots.begin(), slots.end());
}

void CDynamicKFSLAM2D::applyObjectMotion()
{
	const auto index = indexObjects(m_slots, m_step);
	for (const auto& [obj, os] : index)
	{
		const int d = m_router->registry().at(obj).poseDim();
		std::vector<int> steps;
		for (const size_t s : os.poseA) steps.push_back(m_slots[s].step);
		for (const auto& pm : m_motion->select(obj, m_step, steps, d))
		{
			std::vector<int> base;
			for (const int st : pm.steps)
			{
				const auto it = std::find(steps.begin(), steps.end(), st);
				base.push_back(int(slotStateIndex(os.poseA[size_t(it - steps.begin())])));
			}
			auto x = m_xkk.asEigen();
			auto P = m_pkk.asEigen();
			ekf::pseudoMeasurementUpdate(
			    x, P, base, d, [&](const std::vector<Eigen::VectorXd>& v, std::vector<Eigen::MatrixXd>* J) {
				    return m_motion->residual(pm, v, J);
			    }, pm.R);
			++m_report.smoothing_updates;
		}
	}
}

void CDynamicKFSLAM2D::planDrops(TPending& plan)
{
	// Over the slots extended by the pending ones; only existing entries can be old enough to
	// be recorded (a pending pose is the newest of its object, K >= 1), so marginals come from P.
	const std::vector<TSlot> ext = extendedSlots(plan);
	std::vector<size_t>& remove = plan.remove;
	// Time-t features, once they have served the pose augmentation (stale ones from earlier
	// steps may already be listed by planFeatures).
	if (m_drop.dropTimeT())
	{
		std::vector<bool> listed(ext.size(), false);
		for (const size_t s : remove) listed[s] = true;
		for (size_t s = 0; s < ext.size(); ++s)
			if (ext[s].kind == SlotKind::ObjectFeatureT && !listed[s])
			{
				remove.push_back(s);
				++m_report.dropped_time_t;
			}
	}
	// Object poses beyond the last K: recorded with their marginal covariance.
	for (const auto& [obj, os] : indexObjects(ext, m_step))
	{
		const size_t nd = m_drop.posesToDrop(os.poseA.size());
		for (size_t i = 0; i < nd; ++i)
		{
			const size_t sA = os.poseA[i];
			if (sA >= m_slots.size())
				throw std::logic_error("CDynamicKFSLAM2D: a pose added in this step is dropped");
			const bool rigid = sA + 1 < m_slots.size() &&
			                   m_slots[sA + 1].kind == SlotKind::ObjectPoseB &&
			                   m_slots[sA + 1].object == obj;
			const size_t k = slotStateIndex(sA);
			std::vector<int> idx{int(k), int(k + 1)};
			if (rigid) idx.push_back(int(k + 2));
			estimator::TPoseRecord e;
			e.step = m_slots[sA].step;
			e.dim = int(idx.size());
			const auto P = m_pkk.asEigen();
			for (int i = 0; i < e.dim; ++i)
			{
				e.mean[i] = m_xkk[idx[i]];
				for (int j = 0; j < e.dim; ++j) e.cov(i, j) = P(idx[i], idx[j]);
			}
			m_router->registry().recordDroppedPose(obj, e, m_drop.record());
			remove.push_back(sA);
			if (rigid) remove.push_back(sA + 1);
			++m_report.dropped_poses;
		}
	}
	// Static landmarks unseen for too long (optional; never one added in this step).
	for (size_t s = 0; s < m_slots.size(); ++s)
		{
			const TSlot& t = m_slots[s];
			if (t.kind != SlotKind::StaticLandmark || !m_drop.staticDue(t.id, m_step, t.step))
				continue;
			const size_t k = slotStateIndex(s);
			TStaticLandmarkEstimate e;
			e.id = t.id;
			e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
			e.cov = ekf::marginal(m_pkk.asEigen(), {int(k), int(k + 1)});
			e.in_state = false;
			if (m_drop.record()) m_droppedStatic.push_back(e);
			m_drop.forget(t.id);  // only landmarks in the state are tracked
			remove.push_back(s);
			++m_report.dropped_static;
		}
}

void CDynamicKFSLAM2D::commit(TPending& plan)
{
	const Eigen::Index n = m_xkk.size(), ma = plan.a.mean.size(), mb = plan.b.mean.size(),
	                   m = ma + mb;
	if (m == 0 && plan.remove.empty()) return;
	if (m != Eigen::Index(2 * plan.slots.size()))
		throw std::logic_error("CDynamicKFSLAM2D::commit: inconsistent block sizes");
	if (ma == 0) plan.a.cross.resize(0, n);
	const size_t S = m_slots.size() + plan.slots.size();
	std::vector<bool> dropSlot(S, false);
	std::vector<int> rem;
	for (const size_t s : plan.remove)
	{
		if (s >= S) throw std::out_of_range("CDynamicKFSLAM2D::commit: slot index");
		dropSlot[s] = true;
		rem.push_back(int(slotStateIndex(s)));
		rem.push_back(int(slotStateIndex(s)) + 1);
	}
	const std::vector<int> keep = ekf::keptIndices(int(n + m), rem);
	const Eigen::Index N = Eigen::Index(keep.size());

	// The new covariance is written once, into the spare matrix, which then becomes m_pkk (the
	// old one becomes the spare): no allocation while the state size stays the same.
	if (m_pkkSpare.rows() != N)
	{
		KFMatrix fresh(static_cast<size_t>(N), static_cast<size_t>(N));
		m_pkkSpare.swap(fresh);
	}
	auto Pn = m_pkkSpare.asEigen();
	ekf::assembleExtended(m_pkk.asEigen(), plan.a, plan.b, keep, Pn);
	m_pkk.swap(m_pkkSpare);
	Eigen::VectorXd x(n + m);
	x << m_xkk.asEigen(), plan.a.mean, plan.b.mean;
	const Eigen::VectorXd xn = x(keep);
	m_xkk.resize(size_t(N));
	m_xkk.asEigen() = xn;

	std::vector<TSlot> slots;
	slots.reserve(S);
	for (size_t s = 0; s < S; ++s)
		if (!dropSlot[s])
			slots.push_back(s < m_slots.size() ? m_slots[s] : plan.slots[s - m_slots.size()]);
	m_slots.swap(slots);
	m_staticSlot.clear();
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (m_slots[s].kind == SlotKind::StaticLandmark) m_staticSlot[m_slots[s].id] = s;
	plan = TPending();
}

}  // namespace dynslam
