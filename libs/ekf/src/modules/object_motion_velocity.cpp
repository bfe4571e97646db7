/** The object-centric motion models' module (object_motion.h): the velocity of a new object from
 * its first sightings (AfterMotion) and the fallback of a lost object (PlanDrops,
 * cv_fallback_steps; doc/state-layout.md "Object-centric motion models"). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>

#include <stdexcept>

#include "object_motion.h"

namespace dynslam::ekf
{
using estimator::BlockKind;
using estimator::TBlock;

bool CObjectMotionModule::velocityInit(TFilterAccess& a, int32_t obj, size_t pose,
                                       TVelocityInit& out)
{
	const estimator::CPaddedLayout& layout = a.layout();
	const int step = a.step();
	const std::vector<int> ip = layout.indices(pose);
	const int d = a.motion().velocityDim(int(ip.size()));
	if (d == 0) return false;
	const auto x = a.mean();
	Eigen::VectorXd xi = x(ip);
	int steps = step - a.router().registry().at(obj).first_step;
	std::vector<int> ipPrev;  // after a fallback: the pose before this one
	if (m_awaitingVel.count(obj))
	{
		size_t prev = SIZE_MAX;
		for (size_t b = 0; b < layout.size(); ++b)
			if (layout[b].kind == BlockKind::ObjectPose && layout[b].object == obj &&
			    layout[b].step < step && (prev == SIZE_MAX || layout[b].step > layout[prev].step))
				prev = b;
		if (prev == SIZE_MAX) return false;  // one pose since the fallback: wait for the next
		ipPrev = layout.indices(prev);
		for (size_t i = 0; i < ipPrev.size(); ++i)  // the motion between the two poses (a loop:
			xi[Eigen::Index(i)] -= x[ipPrev[i]];    // GCC 12 warns on x(ipPrev) here)
		if (xi.size() == 3) xi[2] = models::wrapToPi(xi[2]);
		steps = step - layout[prev].step;
	}
	Eigen::MatrixXd J_v_xi, Sigma;
	const Eigen::VectorXd v = a.motion().initialVelocity(xi, steps, &J_v_xi, &Sigma);
	TBlock& b = out.block;
	b.kind = BlockKind::ObjectVelocity;
	b.object = obj;
	b.step = step;
	b.dim = d;
	const Eigen::Index m = 2 * b.slots();
	out.G = Eigen::MatrixXd::Zero(m, x.size());
	out.G(Eigen::seqN(0, d), ip) = J_v_xi;
	if (!ipPrev.empty()) out.G(Eigen::seqN(0, d), ipPrev) = -J_v_xi;
	out.mean = Eigen::VectorXd::Zero(m);
	out.mean.head(d) = v;
	out.prior = Eigen::MatrixXd::Identity(m, m);  // pads: 1
	out.prior.topLeftCorner(d, d) = Sigma;
	if (!ipPrev.empty())
	{
		m_awaitingVel.erase(obj);
		m_reinitNow.insert(obj);
		++a.report().object_reinits;
	}
	return true;
}

void CObjectMotionModule::planObjectVelocities(TFilterAccess& a, TPending& plan)
{
	const estimator::CPaddedLayout& layout = a.layout();
	const Eigen::Index n = a.mean().size();
	std::vector<Eigen::MatrixXd> Gs;  // rows of G (the velocity as a function of the state)
	std::vector<Eigen::VectorXd> means;
	std::vector<Eigen::MatrixXd> priors;
	for (const auto& [obj, st] : objectStates(layout))
	{
		if (st.velocity != SIZE_MAX || st.pose == SIZE_MAX || layout[st.pose].step != a.step())
			continue;
		TVelocityInit vi;
		if (!velocityInit(a, obj, st.pose, vi)) continue;
		Gs.push_back(vi.G);
		means.push_back(vi.mean);
		priors.push_back(vi.prior);
		plan.blocks.push_back(vi.block);
	}
	if (Gs.empty()) return;
	Eigen::Index m = 0;
	for (const auto& G : Gs) m += G.rows();
	Eigen::MatrixXd G(m, n), prior = Eigen::MatrixXd::Zero(m, m);
	Eigen::VectorXd mean(m);
	for (size_t i = 0, r = 0; i < Gs.size(); r += size_t(Gs[i].rows()), ++i)
	{
		G.middleRows(Eigen::Index(r), Gs[i].rows()) = Gs[i];
		mean.segment(Eigen::Index(r), Gs[i].rows()) = means[i];
		prior.block(Eigen::Index(r), Eigen::Index(r), Gs[i].rows(), Gs[i].rows()) = priors[i];
	}
	plan.a.mean = mean;
	plan.a.cross = G * a.cov();
	plan.a.cov = plan.a.cross * G.transpose() + prior;
}

void CObjectMotionModule::planFallbacks(TFilterAccess& a, TPending& plan)
{
	if (m_lostNow.empty() && m_reinitNow.empty()) return;
	const estimator::CPaddedLayout ext = a.extendedLayout(plan);
	const estimator::CPaddedLayout& layout = a.layout();
	std::set<size_t> listed(plan.remove.begin(), plan.remove.end());
	const auto P = a.cov();
	const auto remove = [&](size_t b)
	{
		if (!listed.insert(b).second) return;
		if (ext[b].kind == BlockKind::ObjectPose)  // recorded like a dropped pose
		{
			const std::vector<int> idx = layout.indices(b);
			estimator::TPoseRecord e;
			e.step = layout[b].step;
			e.dim = int(idx.size());
			e.mean.head(e.dim) = a.mean()(idx);
			e.cov.topLeftCorner(e.dim, e.dim) = ekf::marginal(P, idx);
			a.router().registry().recordDroppedPose(ext[b].object, e, a.dropPolicy().record());
			++a.report().dropped_poses;
		}
		plan.remove.push_back(b);
	};
	// Lost: velocity and pose leave the state (marginalised out); the object's f_0 stay, and
	// its next readings are time-t features again (the paper's formulation, Alg. 3, 4).
	// Re-initialised: the older pose that gave the velocity goes (one pose per object).
	std::map<int32_t, size_t> newest;
	for (size_t b = 0; b < ext.size(); ++b)
		if (ext[b].kind == BlockKind::ObjectPose && m_reinitNow.count(ext[b].object))
		{
			const auto it = newest.find(ext[b].object);
			if (it == newest.end() || ext[it->second].step < ext[b].step) newest[ext[b].object] = b;
		}
	for (size_t b = 0; b < ext.size(); ++b)
	{
		const TBlock& t = ext[b];
		const bool lost = m_lostNow.count(t.object) != 0;
		if (lost && (t.kind == BlockKind::ObjectVelocity || t.kind == BlockKind::ObjectPose))
		{
			if (b >= layout.size())
				throw std::logic_error("CDynamicKFSLAM2D: a lost object has a pending block");
			remove(b);
		}
		else if (t.kind == BlockKind::ObjectPose && m_reinitNow.count(t.object) &&
		         newest.at(t.object) != b)
			remove(b);
	}
	for (const int32_t obj : m_lostNow)
	{
		m_awaitingVel.insert(obj);
		++a.report().object_fallbacks;
	}
	m_lostNow.clear();
	m_reinitNow.clear();
}
}  // namespace dynslam::ekf
