/** The object-centric motion models' module (object_motion.h): when it is made, its hooks, and
 * the prediction of the objects with a velocity (AfterPropagate). */
#include "object_motion.h"

#include <dynslam/core/ekf_steps.h>

#include <stdexcept>

namespace dynslam::ekf
{
using estimator::BlockKind;
using estimator::TBlock;

std::unique_ptr<CObjectMotionModule> makeObjectMotionModule(TFilterAccess& a)
{
	if (!a.motion().objectCentric()) return nullptr;
	return std::make_unique<CObjectMotionModule>();
}

unsigned CObjectMotionModule::hooks() const
{
	return hookBit(Hook::AfterPropagate) | hookBit(Hook::AfterStaticUpdate) |
	       hookBit(Hook::AfterMotion) | hookBit(Hook::PlanDrops) | hookBit(Hook::ObjectForgotten);
}

void CObjectMotionModule::objectForgotten(int32_t obj)
{
	m_lostNow.erase(obj);
	m_awaitingVel.erase(obj);
	m_reinitNow.erase(obj);
}

std::map<int32_t, CObjectMotionModule::TObjectState> CObjectMotionModule::objectStates(
    const estimator::CPaddedLayout& L)
{
	std::map<int32_t, TObjectState> out;
	for (size_t b = 0; b < L.size(); ++b)
	{
		if (L[b].kind == BlockKind::ObjectPose) out[L[b].object].pose = b;  // ascending step
		if (L[b].kind == BlockKind::ObjectVelocity) out[L[b].object].velocity = b;
	}
	return out;
}

std::vector<int> CObjectMotionModule::concat(std::vector<int> a, const std::vector<int>& b)
{
	a.insert(a.end(), b.begin(), b.end());
	return a;
}

std::set<int32_t> CObjectMotionModule::objectsWithVelocity(const estimator::CPaddedLayout& L)
{
	std::set<int32_t> out;
	for (const TBlock& t : L.blocks())
		if (t.kind == BlockKind::ObjectVelocity) out.insert(t.object);
	return out;
}

void CObjectMotionModule::predictObjects(TFilterAccess& a)
{
	const estimator::CPaddedLayout& layout = a.layout();
	estimator::CObjectRegistry& registry = a.router().registry();
	const bool record = a.dropPolicy().record();
	auto x = a.mean();
	auto P = a.cov();
	for (const auto& [obj, st] : objectStates(layout))
	{
		if (st.velocity == SIZE_MAX) continue;
		if (st.pose == SIZE_MAX)
			throw std::logic_error("CDynamicKFSLAM2D: an object velocity without a pose");
		const std::vector<int> ip = layout.indices(st.pose);
		// The pose of the previous step is replaced by the prediction: recorded like a drop.
		estimator::TPoseRecord e;
		e.step = layout[st.pose].step;
		e.dim = int(ip.size());
		e.mean.head(e.dim) = x(ip);
		e.cov.topLeftCorner(e.dim, e.dim) = ekf::marginal(P, ip);
		registry.recordDroppedPose(obj, e, record);
		const std::vector<int> iv = layout.indices(st.velocity);
		// The velocity: the block's first e.dim entries (further ones are the model's, e.g. ca's
		// acceleration; doc/state-layout.md).
		const std::vector<int> ivel(iv.begin(), iv.begin() + e.dim);
		estimator::TVelocityRecord ev;
		ev.step = e.step;
		ev.dim = e.dim;
		ev.velocity.head(ev.dim) = x(ivel);
		ev.cov.topLeftCorner(ev.dim, ev.dim) = ekf::marginal(P, ivel);
		registry.recordDroppedVelocity(obj, ev, record);

		const std::vector<int> idx = concat(ip, iv);
		if (a.motion().modeCount() > 0)  // object_model = mm (object_motion_modes.cpp)
			predictObjectModes(a, obj, idx);
		else
		{
			Eigen::MatrixXd F, Q;
			const Eigen::VectorXd s = a.motion().predict(x(idx), &F, &Q);
			ekf::predictSubset(x, P, idx, s, F, Q);
		}
		a.setBlockStep(st.pose, a.step());
	}
	if (!m_modes.probabilities().empty()) m_modes.forget(objectsWithVelocity(layout));
	a.layoutChanged();
}
}  // namespace dynslam::ekf
