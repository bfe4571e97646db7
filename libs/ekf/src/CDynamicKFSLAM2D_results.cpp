/** CDynamicKFSLAM2D: result getters (the options are dynslam/model_options.h). */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/backend_results.h>
#include <dynslam/config_utils.h>
#include <dynslam/ekf_steps.h>

#include <algorithm>
#include <ostream>
#include <stdexcept>

namespace dynslam
{

// ------------------------------------------------------------------------------------------
// Results
// ------------------------------------------------------------------------------------------
mrpt::poses::CPosePDFGaussian CDynamicKFSLAM2D::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	p.mean = mrpt::poses::CPose2D(m_xkk[0], m_xkk[1], m_xkk[2]);
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) p.cov(i, j) = m_pkk(i, j);
	return p;
}

std::vector<TStaticLandmarkEstimate> CDynamicKFSLAM2D::getStaticLandmarks(bool includeDropped) const
{
	std::vector<TStaticLandmarkEstimate> out;
	for (size_t s = 0; s < m_slots.size(); ++s)
	{
		if (m_slots[s].kind != SlotKind::StaticLandmark) continue;
		const size_t k = slotStateIndex(s);
		TStaticLandmarkEstimate e;
		e.id = m_slots[s].id;
		e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
		e.cov << m_pkk(k, k), m_pkk(k, k + 1), m_pkk(k + 1, k), m_pkk(k + 1, k + 1);
		e.in_state = true;
		out.push_back(e);
	}
	if (includeDropped) out.insert(out.end(), m_droppedStatic.begin(), m_droppedStatic.end());
	return out;
}

std::vector<TObjectFeatureEstimate> CDynamicKFSLAM2D::getObjectFeatures() const
{
	std::vector<TObjectFeatureEstimate> out;
	for (size_t s = 0; s < m_slots.size(); ++s)
	{
		const TSlot& t = m_slots[s];
		if (t.kind != SlotKind::ObjectFeature0 && t.kind != SlotKind::ObjectFeatureT) continue;
		const size_t k = slotStateIndex(s);
		TObjectFeatureEstimate e;
		e.object = t.object;
		e.feature = t.feature;
		e.id = t.id;
		e.at_time0 = t.kind == SlotKind::ObjectFeature0;
		e.step = t.step;
		e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
		e.cov << m_pkk(k, k), m_pkk(k, k + 1), m_pkk(k + 1, k), m_pkk(k + 1, k + 1);
		out.push_back(e);
	}
	return out;
}

std::map<int32_t, TObjectTrack> CDynamicKFSLAM2D::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(m_router->registry());
	for (size_t s = 0; s < m_slots.size(); ++s)
	{
		const TSlot& t = m_slots[s];
		if (t.kind != SlotKind::ObjectPoseA) continue;
		const bool rigid = s + 1 < m_slots.size() && m_slots[s + 1].kind == SlotKind::ObjectPoseB;
		const int k = int(slotStateIndex(s));
		std::vector<int> idx{k, k + 1};
		if (rigid) idx.push_back(k + 2);
		TObjectPoseEstimate e;
		e.step = t.step;
		e.mean = m_xkk.asEigen()(idx);
		e.cov = ekf::marginal(m_pkk.asEigen(), idx);
		e.in_state = true;
		out[t.object].poses.push_back(e);
	}
	sortTrackPoses(out);
	return out;
}

std::vector<size_t> CDynamicKFSLAM2D::padIndices() const
{
	std::vector<size_t> out;
	for (size_t s = 0; s < m_slots.size(); ++s)
		if (m_slots[s].kind == SlotKind::ObjectPoseB) out.push_back(slotStateIndex(s) + 1);
	return out;
}

void CDynamicKFSLAM2D::getStateWithoutPads(
	Eigen::VectorXd& x, Eigen::MatrixXd& P, std::vector<std::string>* labels) const
{
	const auto pads = padIndices();
	const std::vector<int> keep =
		ekf::keptIndices(int(m_xkk.size()), std::vector<int>(pads.begin(), pads.end()));
	x = m_xkk.asEigen()(keep);
	P = m_pkk.asEigen()(keep, keep);
	if (!labels) return;
	labels->assign({"ego.x", "ego.y", "ego.theta"});
	for (const TSlot& t : m_slots)
	{
		const std::string o = "obj" + std::to_string(t.object);
		switch (t.kind)
		{
			case SlotKind::StaticLandmark:
				labels->push_back("lm" + std::to_string(t.id) + ".x");
				labels->push_back("lm" + std::to_string(t.id) + ".y");
				break;
			case SlotKind::ObjectFeature0:
			case SlotKind::ObjectFeatureT:
			{
				const std::string f = o + ".f" + std::to_string(t.feature) +
									  (t.kind == SlotKind::ObjectFeature0 ? ".t0" : ".t") +
									  (t.kind == SlotKind::ObjectFeatureT ? std::to_string(t.step) : "");
				labels->push_back(f + ".x");
				labels->push_back(f + ".y");
				break;
			}
			case SlotKind::ObjectPoseA:
				labels->push_back(o + ".xi" + std::to_string(t.step) + ".dx");
				labels->push_back(o + ".xi" + std::to_string(t.step) + ".dy");
				break;
			case SlotKind::ObjectPoseB:
				labels->push_back(o + ".xi" + std::to_string(t.step) + ".dtheta");
				break;
		}
	}
}
}  // namespace dynslam
