/** CDynamicKFSLAM2D: the steps for moving objects (Alg. 3 for object features, Alg. 4, Alg. 6)
 * and the drop policies, all through the dense step functions of dynslam/ekf_steps.h. */
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
	std::map<int32_t, size_t> f0;  ///< feature index -> slot
	std::vector<size_t> ft;  ///< time-t feature slots of the current step
	std::vector<size_t> poseA;  ///< pose part-A slots, ascending step
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
				out[t.object].f0[t.feature] = s;
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

void CDynamicKFSLAM2D::augmentObjectFeatures()
{
	if (m_objectMeas.empty()) return;
	// Time-t features left from an earlier step (drop_time_t_features = false) are replaced
	// by this step's for the objects seen now.
	std::set<int32_t> seenObjects;
	for (const auto& m : m_objectMeas) seenObjects.insert(ids::objectOf(m.id));
	std::vector<size_t> stale;
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (m_slots[s].kind == SlotKind::ObjectFeatureT && seenObjects.count(m_slots[s].object))
			stale.push_back(s);
	if (!stale.empty())
	{
		m_report.dropped_time_t += stale.size();
		removeSlots(stale);
	}

	std::vector<Eigen::Vector2d> z;
	std::vector<TSlot> slots;
	for (const auto& m : m_objectMeas)
	{
		const int32_t obj = ids::objectOf(m.id), k = ids::featureOf(m.id);
		auto it = m_objects.find(obj);
		TSlot s;
		s.id = m.id;
		s.object = obj;
		s.feature = k;
		s.step = m_step;
		if (it == m_objects.end() || it->second.first_step == m_step)
		{
			// First sighting (time 0 of this object): the features seen now define it.
			TObjectInfo& info = m_objects[obj];
			info.first_step = m_step;
			info.feature_ids.push_back(m.id);
			s.kind = SlotKind::ObjectFeature0;
			++m_report.object_features_new;
		}
		else if (std::find(it->second.feature_ids.begin(), it->second.feature_ids.end(), m.id) !=
				 it->second.feature_ids.end())
		{
			s.kind = SlotKind::ObjectFeatureT;
			++m_report.object_features_t;
		}
		else
		{
			// Documented skip: a feature not seen at the object's time 0 has no f_0.
			++m_report.skipped_unknown_object_feature;
			continue;
		}
		z.push_back(m.z);
		slots.push_back(s);
	}
	if (z.empty()) return;
	const auto P = m_pkk.asEigen();
	const ekf::Augmentation a = ekf::featureAugmentation(
		options.measurement_model, Eigen::Vector3d(m_xkk[0], m_xkk[1], m_xkk[2]), P.topRows(3), z,
		options.Sigma_v);
	appendSlots(a.mean, a.cross, a.cov, slots, false);
}

void CDynamicKFSLAM2D::augmentObjectPoses()
{
	const auto index = indexObjects(m_slots, m_step);
	for (const auto& [obj, os] : index)
	{
		if (os.ft.empty()) continue;
		const TObjectInfo& info = m_objects.at(obj);
		const int n = int(info.feature_ids.size()), m = int(os.ft.size());
		if (n >= 2 && m < 2)
		{
			++m_report.skipped_pose_degenerate;  // rotation undetermined from one feature
			continue;
		}
		std::vector<int> f0_idx, ft_idx, seen;
		for (const int32_t id : info.feature_ids)
			f0_idx.push_back(int(slotStateIndex(os.f0.at(ids::featureOf(id)))));
		for (const size_t s : os.ft)
		{
			ft_idx.push_back(int(slotStateIndex(s)));
			const auto pos =
				std::find(info.feature_ids.begin(), info.feature_ids.end(), m_slots[s].id);
			seen.push_back(int(pos - info.feature_ids.begin()));
		}
		ekf::Augmentation a;
		try
		{
			a = ekf::objectPoseAugmentation(
				m_xkk.asEigen(), m_pkk.asEigen(), f0_idx, ft_idx, seen, options.Sigma_xi);
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
		std::vector<TSlot> slots{sa};
		if (a.mean.size() == 3)
		{
			TSlot sb = sa;
			sb.kind = SlotKind::ObjectPoseB;
			slots.push_back(sb);
		}
		appendSlots(a.mean, a.cross, a.cov, slots, a.mean.size() == 3);
		++m_report.object_poses_added;
	}
}

void CDynamicKFSLAM2D::applySmoothing()
{
	if (!options.smoothing) return;
	const auto index = indexObjects(m_slots, m_step);
	for (const auto& [obj, os] : index)
	{
		const size_t np = os.poseA.size();
		if (np < 3) continue;
		const TSlot& c = m_slots[os.poseA[np - 1]];
		const TSlot& b = m_slots[os.poseA[np - 2]];
		const TSlot& a = m_slots[os.poseA[np - 3]];
		if (c.step != m_step || b.step != m_step - 1 || a.step != m_step - 2) continue;
		const int d = m_objects.at(obj).feature_ids.size() == 1 ? 2 : 3;
		auto x = m_xkk.asEigen();
		auto P = m_pkk.asEigen();
		ekf::smoothingUpdate(
			x, P, int(slotStateIndex(os.poseA[np - 3])), int(slotStateIndex(os.poseA[np - 2])),
			int(slotStateIndex(os.poseA[np - 1])), options.Sigma_s.topLeftCorner(d, d));
		++m_report.smoothing_updates;
	}
}

void CDynamicKFSLAM2D::applyDropPolicies()
{
	std::vector<size_t> remove;
	// Time-t features, once they have served the pose augmentation.
	if (options.drop_time_t_features)
		for (size_t s = 0; s < m_slots.size(); ++s)
			if (m_slots[s].kind == SlotKind::ObjectFeatureT)
			{
				remove.push_back(s);
				++m_report.dropped_time_t;
			}
	// Object poses beyond the last K: recorded with their marginal covariance.
	const auto index = indexObjects(m_slots, m_step);
	for (const auto& [obj, os] : index)
	{
		const size_t np = os.poseA.size(), K = size_t(options.keep_last_poses);
		for (size_t i = 0; np > K && i < np - K; ++i)
		{
			const size_t sA = os.poseA[i];
			const bool rigid = sA + 1 < m_slots.size() &&
							   m_slots[sA + 1].kind == SlotKind::ObjectPoseB &&
							   m_slots[sA + 1].object == obj;
			const size_t k = slotStateIndex(sA);
			std::vector<int> idx{int(k), int(k + 1)};
			if (rigid) idx.push_back(int(k + 2));
			TObjectPoseEstimate e;
			e.step = m_slots[sA].step;
			e.mean = m_xkk.asEigen()(idx);
			e.cov = ekf::marginal(m_pkk.asEigen(), idx);
			e.in_state = false;
			m_objects.at(obj).dropped_poses.push_back(e);
			remove.push_back(sA);
			if (rigid) remove.push_back(sA + 1);
			++m_report.dropped_poses;
		}
	}
	// Static landmarks unseen for too long (optional).
	if (options.drop_static_after_unseen_steps > 0)
		for (size_t s = 0; s < m_slots.size(); ++s)
		{
			const TSlot& t = m_slots[s];
			if (t.kind != SlotKind::StaticLandmark) continue;
			const auto it = m_staticLastSeen.find(t.id);
			const int last = it == m_staticLastSeen.end() ? t.step : it->second;
			if (m_step - last < options.drop_static_after_unseen_steps) continue;
			const size_t k = slotStateIndex(s);
			TStaticLandmarkEstimate e;
			e.id = t.id;
			e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
			e.cov = ekf::marginal(m_pkk.asEigen(), {int(k), int(k + 1)});
			e.in_state = false;
			m_droppedStatic.push_back(e);
			remove.push_back(s);
			++m_report.dropped_static;
		}
	if (!remove.empty()) removeSlots(remove);
}

void CDynamicKFSLAM2D::appendSlots(
	const Eigen::VectorXd& mean, const Eigen::MatrixXd& cross, const Eigen::MatrixXd& cov,
	const std::vector<TSlot>& slots, bool lastEntryIsPad)
{
	const Eigen::Index n = m_xkk.size(), m0 = mean.size(), m = m0 + (lastEntryIsPad ? 1 : 0);
	if (m != Eigen::Index(2 * slots.size()) || cross.rows() != m0 || cross.cols() != n ||
		cov.rows() != m0 || cov.cols() != m0)
		throw std::logic_error("CDynamicKFSLAM2D::appendSlots: inconsistent block sizes");
	m_xkk.resize(n + m);
	m_pkk.setSize(n + m, n + m);  // keeps the old block; new entries are zero
	auto x = m_xkk.asEigen();
	auto P = m_pkk.asEigen();
	x.segment(n, m0) = mean;
	P.block(n, 0, m0, n) = cross;
	P.block(0, n, n, m0) = cross.transpose();
	P.block(n, n, m0, m0) = cov;
	if (lastEntryIsPad)
	{
		// The pad: independent, unit variance, zero mean; no model ever touches it.
		x[n + m0] = 0;
		P.row(n + m0).setZero();
		P.col(n + m0).setZero();
		P(n + m0, n + m0) = 1.0;
	}
	m_slots.insert(m_slots.end(), slots.begin(), slots.end());
}

void CDynamicKFSLAM2D::removeSlots(const std::vector<size_t>& slotIdx)
{
	if (slotIdx.empty()) return;
	const int n = int(m_xkk.size());
	std::vector<int> rem;
	std::vector<bool> dropSlot(m_slots.size(), false);
	for (const size_t s : slotIdx)
	{
		if (s >= m_slots.size()) throw std::out_of_range("CDynamicKFSLAM2D::removeSlots");
		dropSlot[s] = true;
		rem.push_back(int(slotStateIndex(s)));
		rem.push_back(int(slotStateIndex(s)) + 1);
	}
	const std::vector<int> keep = ekf::keptIndices(n, rem);
	const Eigen::VectorXd x = m_xkk.asEigen()(keep);
	const ekf::RowMatrixXd P = m_pkk.asEigen()(keep, keep);
	m_xkk.resize(keep.size());
	m_xkk.asEigen() = x;
	m_pkk.setSize(keep.size(), keep.size());
	m_pkk.asEigen() = P;

	std::vector<TSlot> slots;
	slots.reserve(m_slots.size());
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (!dropSlot[s]) slots.push_back(m_slots[s]);
	m_slots.swap(slots);
	m_staticSlot.clear();
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (m_slots[s].kind == SlotKind::StaticLandmark) m_staticSlot[m_slots[s].id] = s;
}
}  // namespace dynslam
