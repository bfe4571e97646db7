/** CDynamicKFSLAM2D: the steps of object-centric motion models (IObjectMotionModel with
 * velocityDim() > 0, e.g. estimator::CConstantVelocity, `object_model = cv`; issue 13):
 * prediction of every object's pose and velocity, measurement updates of ego, object pose and
 * body-frame features by every sighting of an object feature, and the velocity of a new object
 * from its first two sightings (doc/state-layout.md "Object-centric motion models"). With the
 * paper's models (velocityDim() == 0) every function here does nothing. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "object_sighting.h"

namespace dynslam
{
using estimator::BlockKind;
using estimator::TBlock;

namespace
{
/** An object's state blocks: its newest pose and its velocity (if any). */
struct TObjectState
{
	size_t pose = SIZE_MAX, velocity = SIZE_MAX;
};
std::map<int32_t, TObjectState> objectStates(const estimator::CPaddedLayout& L)
{
	std::map<int32_t, TObjectState> out;
	for (size_t b = 0; b < L.size(); ++b)
	{
		if (L[b].kind == BlockKind::ObjectPose) out[L[b].object].pose = b;  // ascending step
		if (L[b].kind == BlockKind::ObjectVelocity) out[L[b].object].velocity = b;
	}
	return out;
}

/** The used readings of an object stacked into one update: H, nu and R = blockdiag(Sigma_v +
 * cth h h^T), h = the reading's column on the ego heading (H's column 2), cth = c P_thth
 * (cv_heading_inflation; 0: R = blockdiag(Sigma_v), today's update). The reading gate of
 * objectFeatureUpdates keeps Sigma_v: it tests the honest innovation covariance, the inflation
 * is not the reading's noise (doc/state-layout.md "Heading inflation of object readings"). */
void stackReadings(const std::vector<Eigen::MatrixXd>& Hs, const std::vector<Eigen::Vector2d>& nus,
                   const Eigen::Matrix2d& Sigma_v, double cth, Eigen::MatrixXd& H,
                   Eigen::VectorXd& nu, Eigen::MatrixXd& R)
{
	const Eigen::Index m = Eigen::Index(Hs.size());
	H.resize(2 * m, Hs.front().cols());
	nu.resize(2 * m);
	R = Eigen::MatrixXd::Zero(2 * m, 2 * m);
	for (Eigen::Index r = 0; r < m; ++r)
	{
		H.middleRows(2 * r, 2) = Hs[size_t(r)];
		nu.segment(2 * r, 2) = nus[size_t(r)];
		R.block(2 * r, 2 * r, 2, 2) = Sigma_v;
		const Eigen::Vector2d h = Hs[size_t(r)].col(2);  // d z / d ego heading
		if (cth > 0) R.block(2 * r, 2 * r, 2, 2) += cth * h * h.transpose();
	}
}

std::vector<int> concat(std::vector<int> a, const std::vector<int>& b)
{
	a.insert(a.end(), b.begin(), b.end());
	return a;
}

}  // namespace

std::set<int32_t> CDynamicKFSLAM2D::objectsWithVelocity() const
{
	std::set<int32_t> out;
	for (const TBlock& t : m_layout.blocks())
		if (t.kind == BlockKind::ObjectVelocity) out.insert(t.object);
	return out;
}

void CDynamicKFSLAM2D::predictObjects()
{
	if (!m_motion->objectCentric()) return;
	auto x = m_xkk.asEigen();
	auto P = cov();
	for (const auto& [obj, st] : objectStates(m_layout))
	{
		if (st.velocity == SIZE_MAX) continue;
		if (st.pose == SIZE_MAX)
			throw std::logic_error("CDynamicKFSLAM2D: an object velocity without a pose");
		const std::vector<int> ip = m_layout.indices(st.pose);
		// The pose of the previous step is replaced by the prediction: recorded like a drop.
		estimator::TPoseRecord e;
		e.step = m_layout[st.pose].step;
		e.dim = int(ip.size());
		e.mean.head(e.dim) = x(ip);
		e.cov.topLeftCorner(e.dim, e.dim) = ekf::marginal(P, ip);
		m_router->registry().recordDroppedPose(obj, e, m_drop.record());
		const std::vector<int> iv = m_layout.indices(st.velocity);
		// The velocity: the block's first e.dim entries (further ones are the model's, e.g. ca's
		// acceleration; doc/state-layout.md).
		const std::vector<int> ivel(iv.begin(), iv.begin() + e.dim);
		estimator::TVelocityRecord ev;
		ev.step = e.step;
		ev.dim = e.dim;
		ev.velocity.head(ev.dim) = x(ivel);
		ev.cov.topLeftCorner(ev.dim, ev.dim) = ekf::marginal(P, ivel);
		m_router->registry().recordDroppedVelocity(obj, ev, m_drop.record());

		const std::vector<int> idx = concat(ip, iv);
		if (m_motion->modeCount() > 0)  // object_model = mm (CDynamicKFSLAM2D_mm.cpp)
			predictObjectModes(obj, idx);
		else
		{
			Eigen::MatrixXd F, Q;
			const Eigen::VectorXd s = m_motion->predict(x(idx), &F, &Q);
			ekf::predictSubset(x, P, idx, s, F, Q);
		}
		m_layout.setStep(st.pose, m_step);
	}
	if (!m_modes.probabilities().empty()) m_modes.forget(objectsWithVelocity());
	onLayoutChanged();
}

void CDynamicKFSLAM2D::objectFeatureUpdates()
{
	const std::map<int32_t, TObjectState> states = objectStates(m_layout);
	std::map<int32_t, std::vector<estimator::TRoutedReading>> byObject;
	for (const auto& m : m_routed.with(estimator::Route::ObjectTimeT))
	{
		const auto it = states.find(m.object);
		if (it != states.end() && it->second.velocity != SIZE_MAX) byObject[m.object].push_back(m);
	}
	if (byObject.empty()) return;
	// f0 blocks by feature ID
	std::map<int32_t, size_t> f0Block;
	for (size_t b = 0; b < m_layout.size(); ++b)
		if (m_layout[b].kind == BlockKind::ObjectFeature0) f0Block[m_layout[b].id] = b;
	auto x = m_xkk.asEigen();
	auto P = cov();
	const double gate = m_motion->readingGate();
	for (const auto& [obj, readings] : byObject)
	{
		const estimator::TObjectEntry& info = m_router->registry().at(obj);
		const int n = int(info.feature_ids.size());
		const std::vector<int> ip = m_layout.indices(states.at(obj).pose);
		std::vector<int> idx = concat({0, 1, 2}, ip);
		for (const int32_t id : info.feature_ids)
			idx = concat(idx, m_layout.indices(f0Block.at(id)));
		Eigen::Matrix2Xd f0(2, n);
		for (int k = 0; k < n; ++k) f0.col(k) = x.segment(idx[3 + ip.size() + 2 * k], 2);
		const Eigen::Vector3d ego = x.head<3>();
		const Eigen::VectorXd xi = x(ip);
		const Eigen::MatrixXd Pii = P(idx, idx);
		const int d = int(ip.size());
		std::vector<Eigen::MatrixXd> Hs;
		std::vector<Eigen::Vector2d> nus;
		for (const auto& m : readings)
		{
			models::Matrix23d J_z_x;
			Eigen::MatrixXd J_z_xi, J_z_f0;
			const Eigen::Vector2d zhat = detail::sighting(
			    options.measurement_model, ego, m_in.sensor_pose, xi, f0,
			    info.indexOf(m.reading.id), &J_z_x, &J_z_xi, &J_z_f0, info.founders);
			Eigen::MatrixXd H(2, idx.size());
			H << J_z_x, J_z_xi, J_z_f0;
			const Eigen::Vector2d nu =
			    models::innovation(options.measurement_model, m.reading.z, zhat);
			if (std::isfinite(gate))
			{
				const Eigen::Matrix2d S = H * Pii * H.transpose() + options.Sigma_v;
				const double nis = nu.dot(S.ldlt().solve(nu));
				if (nis > gate)
				{
					++m_report.object_gated_out;
					continue;
				}
			}
			Hs.push_back(H);
			nus.push_back(nu);
		}
		// Every reading gated out: the object coasts on its prediction; at the model's count of
		// such steps in a row it is lost (planFallbacks removes its motion state).
		if (m_motion->reportGating(obj, Hs.empty())) m_lostNow.insert(obj);
		if (Hs.empty()) continue;
		const Eigen::Index m = Eigen::Index(Hs.size());
		Eigen::MatrixXd H, R;
		Eigen::VectorXd nu;
		stackReadings(Hs, nus, options.Sigma_v, options.cv.heading_inflation * P(2, 2), H, nu, R);
		ekf::sparseUpdate(x, P, idx, H, nu, R);
		if (d == 3) x[ip[2]] = models::wrapToPi(x[ip[2]]);
		OnNormalizeStateVector();
		m_report.object_feature_updates += size_t(m);
	}
}

bool CDynamicKFSLAM2D::velocityInit(int32_t obj, size_t pose, TVelocityInit& out)
{
	const std::vector<int> ip = m_layout.indices(pose);
	const int d = m_motion->velocityDim(int(ip.size()));
	if (d == 0) return false;
	const auto x = m_xkk.asEigen();
	Eigen::VectorXd xi = x(ip);
	int steps = m_step - m_router->registry().at(obj).first_step;
	std::vector<int> ipPrev;  // after a fallback: the pose before this one
	if (m_awaitingVel.count(obj))
	{
		size_t prev = SIZE_MAX;
		for (size_t b = 0; b < m_layout.size(); ++b)
			if (m_layout[b].kind == BlockKind::ObjectPose && m_layout[b].object == obj &&
			    m_layout[b].step < m_step &&
			    (prev == SIZE_MAX || m_layout[b].step > m_layout[prev].step))
				prev = b;
		if (prev == SIZE_MAX) return false;  // one pose since the fallback: wait for the next
		ipPrev = m_layout.indices(prev);
		for (size_t i = 0; i < ipPrev.size(); ++i)  // the motion between the two poses (a loop:
			xi[Eigen::Index(i)] -= x[ipPrev[i]];    // GCC 12 warns on x(ipPrev) here)
		if (xi.size() == 3) xi[2] = models::wrapToPi(xi[2]);
		steps = m_step - m_layout[prev].step;
	}
	Eigen::MatrixXd J_v_xi, Sigma;
	const Eigen::VectorXd v = m_motion->initialVelocity(xi, steps, &J_v_xi, &Sigma);
	TBlock& b = out.block;
	b.kind = BlockKind::ObjectVelocity;
	b.object = obj;
	b.step = m_step;
	b.dim = d;
	const Eigen::Index m = 2 * b.slots();
	out.G = Eigen::MatrixXd::Zero(m, m_xkk.size());
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
		++m_report.object_reinits;
	}
	return true;
}

void CDynamicKFSLAM2D::planObjectVelocities(TPending& plan)
{
	if (!m_motion->objectCentric()) return;
	const Eigen::Index n = m_xkk.size();
	std::vector<Eigen::MatrixXd> Gs;  // rows of G (the velocity as a function of the state)
	std::vector<Eigen::VectorXd> means;
	std::vector<Eigen::MatrixXd> priors;
	for (const auto& [obj, st] : objectStates(m_layout))
	{
		if (st.velocity != SIZE_MAX || st.pose == SIZE_MAX || m_layout[st.pose].step != m_step)
			continue;
		TVelocityInit vi;
		if (!velocityInit(obj, st.pose, vi)) continue;
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
	plan.a.cross = G * cov();
	plan.a.cov = plan.a.cross * G.transpose() + prior;
}

void CDynamicKFSLAM2D::planFallbacks(TPending& plan)
{
	if (m_lostNow.empty() && m_reinitNow.empty()) return;
	const estimator::CPaddedLayout ext = extendedLayout(plan);
	std::set<size_t> listed(plan.remove.begin(), plan.remove.end());
	const auto P = cov();
	const auto remove = [&](size_t b)
	{
		if (!listed.insert(b).second) return;
		if (ext[b].kind == BlockKind::ObjectPose)  // recorded like a dropped pose
		{
			const std::vector<int> idx = m_layout.indices(b);
			estimator::TPoseRecord e;
			e.step = m_layout[b].step;
			e.dim = int(idx.size());
			e.mean.head(e.dim) = m_xkk.asEigen()(idx);
			e.cov.topLeftCorner(e.dim, e.dim) = ekf::marginal(P, idx);
			m_router->registry().recordDroppedPose(ext[b].object, e, m_drop.record());
			++m_report.dropped_poses;
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
			if (b >= m_layout.size())
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
		++m_report.object_fallbacks;
	}
	m_lostNow.clear();
	m_reinitNow.clear();
}
}  // namespace dynslam
