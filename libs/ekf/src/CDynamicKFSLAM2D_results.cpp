/** CDynamicKFSLAM2D: result getters (the options are dynslam/common/model_options.h). */
#include <dynslam/common/backend_results.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/core/ekf_steps.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <algorithm>
#include <ostream>
#include <stdexcept>

#include "modules/module_list.h"
#include "modules/object_drop.h"
#include "modules/object_motion.h"

namespace dynslam
{
using estimator::BlockKind;
using estimator::TBlock;

// ------------------------------------------------------------------------------------------
// Results
// ------------------------------------------------------------------------------------------
mrpt::poses::CPosePDFGaussian CDynamicKFSLAM2D::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	p.mean = mrpt::poses::CPose2D(m_xkk[0], m_xkk[1], m_xkk[2]);
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) p.cov(i, j) = cov()(i, j);
	if (!options.prior_gauge_anchor) return p;  // no output term: no allocation per call
	const Eigen::MatrixXd g = gaugeTerm(nullptr, m_xkk.asEigen().head<3>());
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) p.cov(i, j) += g(i, j);
	return p;
}

std::vector<TStaticLandmarkEstimate> CDynamicKFSLAM2D::getStaticLandmarks() const
{
	const TStateRef s = wholeState();
	std::vector<TStaticLandmarkEstimate> out;
	for (size_t b = 0; b < s.layout.size(); ++b)
	{
		if (s.layout[b].kind != BlockKind::StaticLandmark) continue;
		const int k = s.layout.first(b);
		TStaticLandmarkEstimate e;
		e.id = s.layout[b].id;
		e.mean = s.x.segment<2>(k);
		e.cov = s.P.block<2, 2>(k, k);
		e.cov += gaugeTerm(&s.layout[b], e.mean);
		e.in_state = true;
		out.push_back(e);
	}
	return out;
}

size_t CDynamicKFSLAM2D::liveObjectCount() const
{
	std::vector<int32_t> objects;
	for (const TBlock& t : m_layout.blocks())
		if (t.kind == BlockKind::ObjectFeature0 || t.kind == BlockKind::ObjectFeatureT ||
		    t.kind == BlockKind::ObjectPose || t.kind == BlockKind::ObjectVelocity)
			objects.push_back(t.object);  // (a Compressed block's `object` is its level)
	std::sort(objects.begin(), objects.end());
	return size_t(std::unique(objects.begin(), objects.end()) - objects.begin());
}

std::vector<TStaticLandmarkEstimate> CDynamicKFSLAM2D::getDroppedStaticLandmarks() const
{
	std::vector<TStaticLandmarkEstimate> out;
	out.reserve(m_droppedStatic.size());
	const TBlock point;  // a static landmark: a world point
	for (TStaticLandmarkEstimate e : m_droppedStatic)
	{
		e.cov += gaugeTerm(&point, e.mean);
		out.push_back(e);
	}
	return out;
}

std::vector<TObjectFeatureEstimate> CDynamicKFSLAM2D::getObjectFeatures() const
{
	std::vector<TObjectFeatureEstimate> out;
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const TBlock& t = m_layout[b];
		if (t.kind != BlockKind::ObjectFeature0 && t.kind != BlockKind::ObjectFeatureT) continue;
		const int k = m_layout.first(b);
		TObjectFeatureEstimate e;
		e.object = t.object;
		e.feature = t.feature;
		e.id = t.id;
		e.at_time0 = t.kind == BlockKind::ObjectFeature0;
		e.step = t.step;
		e.mean = Eigen::Vector2d(m_xkk[k], m_xkk[k + 1]);
		e.cov << cov()(k, k), cov()(k, k + 1), cov()(k + 1, k), cov()(k + 1, k + 1);
		e.cov += gaugeTerm(&t, e.mean);
		out.push_back(e);
	}
	TBlock f0;  // recorded f_0 of dropped objects: their relative covariance plus the gauge's
	f0.kind = BlockKind::ObjectFeature0;
	static const std::vector<TObjectFeatureEstimate> none;
	const ekf::CObjectDropModule* drops =
	    m_modules->objectDrop();  // drop_object_after_unseen_steps
	for (TObjectFeatureEstimate e : drops ? drops->droppedFeatures() : none)
	{
		e.cov += gaugeTerm(&f0, e.mean);
		out.push_back(e);
	}
	return out;
}

std::map<int32_t, TObjectTrack> CDynamicKFSLAM2D::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(m_router->registry());
	for (auto& [obj, track] : out)  // dropped poses: recorded with the relative covariance
		for (TObjectPoseEstimate& e : track.poses)
		{
			TBlock pose;
			pose.kind = BlockKind::ObjectPose;
			pose.dim = int(e.mean.size());
			e.cov += gaugeTerm(&pose, e.mean);
			if (e.velocity.size() == 0) continue;
			TBlock vel;
			vel.kind = BlockKind::ObjectVelocity;
			vel.dim = int(e.velocity.size());
			e.velocity_cov += gaugeTerm(&vel, e.velocity);
		}
	std::map<int32_t, std::vector<int>> velocityIdx;  // object-centric models (cv, ctrv, ca)
	for (size_t b = 0; b < m_layout.size(); ++b)
		if (m_layout[b].kind == BlockKind::ObjectVelocity)
			velocityIdx[m_layout[b].object] = m_layout.indices(b);
	for (size_t b = 0; b < m_layout.size(); ++b)
	{
		const TBlock& t = m_layout[b];
		if (t.kind != BlockKind::ObjectPose) continue;
		const std::vector<int> idx = m_layout.indices(b);
		TObjectPoseEstimate e;
		e.step = t.step;
		e.mean = m_xkk.asEigen()(idx);
		e.cov = ekf::marginal(cov(), idx) + gaugeTerm(&t, e.mean);
		// The velocity belongs to the newest pose: the only one of a velocity model in state.
		if (const auto v = velocityIdx.find(t.object); v != velocityIdx.end() && t.step == m_step)
		{
			// The velocity: the block's first t.dim entries (ca: then its acceleration).
			const std::vector<int> iv(v->second.begin(), v->second.begin() + t.dim);
			e.velocity = m_xkk.asEigen()(iv);
			TBlock vel = t;
			vel.kind = BlockKind::ObjectVelocity;
			vel.dim = int(e.velocity.size());
			e.velocity_cov = ekf::marginal(cov(), iv) + gaugeTerm(&vel, e.velocity);
		}
		e.in_state = true;
		out[t.object].poses.push_back(e);
	}
	sortTrackPoses(out);
	if (const ekf::CObjectMotionModule* motion = m_modules->objectMotion())
		motion->attachModeProbabilities(out);  // object_model = mm
	return out;
}

std::vector<size_t> CDynamicKFSLAM2D::padIndices() const
{
	const std::vector<int> p = wholeState().layout.padIndices();
	return std::vector<size_t>(p.begin(), p.end());
}

namespace
{
/** map = {id -> block} of the (id, block) pairs (the last block of an ID listed twice), updated
 * in place: the nodes of the IDs it keeps are reused (a step's commit used to clear and
 * rebuild the whole map, one allocation per static landmark). */
void assignInPlace(std::map<int32_t, size_t>& map, std::vector<std::pair<int32_t, size_t>>& pairs)
{
	std::stable_sort(pairs.begin(), pairs.end(),
	                 [](const auto& a, const auto& b) { return a.first < b.first; });
	auto it = map.begin();
	for (size_t i = 0; i < pairs.size(); ++i)
	{
		if (i + 1 < pairs.size() && pairs[i + 1].first == pairs[i].first) continue;
		const auto& [id, block] = pairs[i];
		while (it != map.end() && it->first < id) it = map.erase(it);
		if (it != map.end() && it->first == id)
			(it++)->second = block;
		else
			map.emplace_hint(it, id, block);
	}
	map.erase(it, map.end());
}
}  // namespace

void CDynamicKFSLAM2D::onLayoutChanged()
{
	static thread_local std::vector<std::pair<int32_t, size_t>> statics;
	slotsOf(m_layout, m_slots, &statics);
	assignInPlace(m_staticBlock, statics);
}

void CDynamicKFSLAM2D::slotsOf(const estimator::CPaddedLayout& layout, std::vector<TSlot>& slots,
                               std::vector<std::pair<int32_t, size_t>>* statics)
{
	slots.clear();
	if (statics) statics->clear();
	for (size_t b = 0; b < layout.size(); ++b)
	{
		const TBlock& t = layout[b];
		TSlot s;
		s.id = t.id;
		s.object = t.object;
		s.feature = t.feature;
		s.step = t.step;
		switch (t.kind)
		{
			case BlockKind::StaticLandmark:
				s.kind = SlotKind::StaticLandmark;
				if (statics) statics->emplace_back(t.id, b);
				break;
			case BlockKind::ObjectFeature0:
				s.kind = SlotKind::ObjectFeature0;
				break;
			case BlockKind::ObjectFeatureT:
				s.kind = SlotKind::ObjectFeatureT;
				break;
			case BlockKind::ObjectPose:
				s.kind = SlotKind::ObjectPoseA;
				s.id = -1;
				break;
			case BlockKind::ObjectVelocity:
				s.kind = SlotKind::ObjectVelocityA;
				s.id = -1;
				break;
			case BlockKind::OdometryBias:
				s.kind = SlotKind::OdometryBias;
				break;
			case BlockKind::Compressed:
				s.kind = SlotKind::Compressed;
				break;
		}
		slots.push_back(s);
		if (t.kind == BlockKind::ObjectPose && t.dim == 3)
		{
			s.kind = SlotKind::ObjectPoseB;  // [dtheta, pad]
			slots.push_back(s);
		}
		// The velocity's further slots: [omega, pad] (cv, ctrv), [omega, ax], [ay, alpha] (ca).
		for (int i = 1; t.kind == BlockKind::ObjectVelocity && i < t.slots(); ++i)
		{
			s.kind = SlotKind::ObjectVelocityB;
			slots.push_back(s);
		}
	}
}

namespace
{
void appendLabels(const TBlock& t, std::vector<std::string>& labels)
{
	const std::string o = "obj" + std::to_string(t.object);
	switch (t.kind)
	{
		case BlockKind::StaticLandmark:
			labels.push_back("lm" + std::to_string(t.id) + ".x");
			labels.push_back("lm" + std::to_string(t.id) + ".y");
			break;
		case BlockKind::ObjectFeature0:
		case BlockKind::ObjectFeatureT:
		{
			const bool t0 = t.kind == BlockKind::ObjectFeature0;
			const std::string f =
			    o + ".f" + std::to_string(t.feature) + (t0 ? ".t0" : ".t" + std::to_string(t.step));
			labels.push_back(f + ".x");
			labels.push_back(f + ".y");
			break;
		}
		case BlockKind::ObjectPose:
		{
			const std::string p = o + ".xi" + std::to_string(t.step);
			labels.push_back(p + ".dx");
			labels.push_back(p + ".dy");
			if (t.dim == 3) labels.push_back(p + ".dtheta");
			break;
		}
		case BlockKind::ObjectVelocity:
			for (int i = 0; i < t.dim; ++i)
				labels.push_back(o + ".v" + std::to_string(t.step) + "." + std::to_string(i));
			break;
		case BlockKind::OdometryBias:
			labels.push_back("odo.b_w");
			if (t.dim == 2) labels.push_back("odo.s");
			break;
		case BlockKind::Compressed:  // never seen by a getter (wholeState() is expanded)
			labels.push_back("c" + std::to_string(t.object) + "." + std::to_string(t.feature) +
			                 ".0");
			labels.push_back("c" + std::to_string(t.object) + "." + std::to_string(t.feature) +
			                 ".1");
			break;
	}
}
}  // namespace

void CDynamicKFSLAM2D::getStateWithoutPads(Eigen::VectorXd& x, Eigen::MatrixXd& P,
                                           std::vector<std::string>* labels) const
{
	const TStateRef s = wholeState();
	const std::vector<int> keep = ekf::keptIndices(int(s.x.size()), s.layout.padIndices());
	x = s.x(keep);
	P = options.prior_gauge_anchor ? Eigen::MatrixXd(reportedCov()(keep, keep))
	                               : Eigen::MatrixXd(s.P(keep, keep));
	if (!labels) return;
	labels->assign({"ego.x", "ego.y", "ego.theta"});
	for (const TBlock& t : s.layout.blocks()) appendLabels(t, *labels);
}
}  // namespace dynslam
