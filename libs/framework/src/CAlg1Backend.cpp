#include <dynslam/common/backend_results.h>
#include <dynslam/common/seam_options.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/models/gauge.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/framework/CAlg1Backend.h>
#include <dynslam/framework/object_pose_step.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <set>
#include <stdexcept>

namespace dynslam::framework
{
CAlg1Backend::CAlg1Backend(const TBackendOptions& opts) : m_opts(opts)
{
	m_opts.validate();
	reset();
}

void CAlg1Backend::reset()
{
	m_cost = CRunningCost();
	m_ego = TVarKey::ego(-1);
	m_anchorPending = m_opts.model.prior_gauge_anchor;  // x_0 fixed: no variable, no prior term
	m_fixedEgo = m_opts.model.initial_pose;
	if (!m_anchorPending)
	{
		m_cost.addVariable(m_ego, m_opts.model.initial_pose);
		m_cost.addTerm(CPriorTerm::fromCovariance({m_ego}, {3}, m_opts.model.initial_pose,
		                                          m_opts.model.Sigma_0));
	}
	m_step = -1;
	if (!m_userRouter) m_router = estimator::routers().make("ids", {});
	m_router->reset();
	if (!m_userMotion) m_motion = makeMotionModel(m_opts.model);
	m_velocitySince.clear();
	m_modes.clear();
	m_drop = estimator::CDropPolicy(m_opts.model.dropOptions());
	m_droppedStatic.clear();
	m_report = TStepReport();
}

void CAlg1Backend::setRouter(std::unique_ptr<estimator::IMeasurementRouter> r)
{
	if (!r) throw std::invalid_argument("CAlg1Backend::setRouter: null");
	m_router = std::move(r);
	m_userRouter = true;
}

void CAlg1Backend::setObjectMotionModel(std::shared_ptr<const estimator::IObjectMotionModel> m)
{
	if (!m) throw std::invalid_argument("CAlg1Backend::setObjectMotionModel: null");
	m_motion = std::move(m);
	m_userMotion = true;
}

TGaussNewtonResult CAlg1Backend::gnAndCollapse()
{
	TGaussNewtonOptions o;
	o.solver = SolverKind::Dense;
	o.compute_covariance = false;
	TGaussNewtonResult r = m_cost.gaussNewtonStep(o);
	m_cost.collapseToPrior(r.information);
	return r;
}

Eigen::MatrixXd CAlg1Backend::marginalCov(const TVarKey& k) const
{
	TGaussNewtonOptions o;
	o.solver = SolverKind::Dense;
	return m_cost.covariance({k}, o);
}

bool CAlg1Backend::isTimeT(const TVarKey& k) const
{
	return k.kind == VarKind::ObjectFeature && m_router->registry().isTimeT(k.id, k.step);
}

void CAlg1Backend::processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
                                            const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	static const std::string who = "CAlg1Backend";
	const estimator::TStepInput in = parseStepInput(action, SF, m_opts.model.parseOptions(), who);
	m_router->validate(in.readings, who);
	++m_step;
	m_sensor = in.sensor_pose;
	m_report = TStepReport();
	m_report.step = m_step;
	const estimator::TRoutedStep routed = m_router->route(
	    m_step, in.readings, [this](int32_t id) { return m_cost.has(TVarKey::landmark(id)); });
	m_report.skipped_unknown_object_feature = routed.skipped_unknown_object_feature;
	m_report.skipped_unknown_id = routed.skipped_unknown_id;  // ID -1: no association here
	propagate(in);                                            // Alg. 7 / Theorem A.5
	predictObjects(routed);             // object-centric models only (cv, ctrv, ca, mm)
	staticSteps(routed);                // Alg. 5 / A.3, then Alg. 3 / A.1
	objectFeatureUpdates(routed);       // object-centric models only
	objectFeatureAugmentation(routed);  // Alg. 3 / A.1 (objects)
	objectPoseAugmentation();           // Alg. 4 / Theorem 4.1
	objectMotion();                     // Alg. 6 / Theorem 4.2 (optional)
	initObjectVelocities();             // object-centric models only
	drops();
}

// Alg. 7 as a marginalization (Theorem A.5).
void CAlg1Backend::propagate(const estimator::TStepInput& in)
{
	if (m_opts.model.skip_prediction_on_empty_map &&
	    m_cost.numVariables() == (m_anchorPending ? 0u : 1u))
		return;
	const Eigen::Matrix3d Su = m_opts.model.motion_noise_from_action ? in.U : m_opts.model.Sigma_w;
	if (m_anchorPending) return propagateAnchored(in.u, Su);
	const TVarKey next = TVarKey::ego(m_step);
	Eigen::Matrix3d F;
	const Eigen::Vector3d pred = models::composePose(m_cost.value(m_ego), in.u, &F);
	if (Su.isZero(0))
	{
		// Noise-free motion: x_t = x_{t-1} (+) u is a change of variables, the limit of the
		// marginalization as Sigma_u -> 0: Omega' = T^-T Omega T^-1, T = blkdiag(F, I).
		if (m_cost.terms().size() != 1)
			throw std::logic_error("CAlg1Backend: the running cost is not a single prior");
		const auto* prior = dynamic_cast<const CPriorTerm*>(m_cost.terms()[0].get());
		const int n = m_cost.totalDim(), e = m_cost.offset(m_ego);
		Eigen::MatrixXd Tinv = Eigen::MatrixXd::Identity(n, n);
		Tinv.block<3, 3>(e, e) = F.inverse();
		const Eigen::MatrixXd Omega = Tinv.transpose() * prior->information() * Tinv;
		CRunningCost c;
		for (const auto& k : m_cost.keys())
			c.addVariable(k == m_ego ? next : k,
			              k == m_ego ? Eigen::VectorXd(pred) : m_cost.value(k));
		m_cost = c;
		m_ego = next;
		m_cost.collapseToPrior(0.5 * (Omega + Omega.transpose()));
		return;
	}
	if (Eigen::LLT<Eigen::Matrix3d>(Su).info() != Eigen::Success)
		throw std::runtime_error(
		    "CAlg1Backend: the odometry covariance is singular but not zero; the framework "
		    "needs it positive definite (or exactly zero)");
	m_cost.addVariable(next, pred);
	m_cost.addTerm(std::make_shared<COdometryTerm>(m_ego.step, m_step, in.u, Su));
	m_cost.marginalize({m_ego});
	m_ego = next;
}

namespace
{
/** A term with one of its variables fixed at a value (prior_gauge = anchor: the ego while it is
 * still exact): the inner term's residual, without that variable's Jacobian. */
class CConditionedTerm : public CTerm
{
public:
	CConditionedTerm(CTermPtr inner, const TVarKey& fixed, Eigen::VectorXd value)
	    : CTerm(others(*inner, fixed)),
	      m_inner(std::move(inner)),
	      m_fixed(fixed),
	      m_value(std::move(value))
	{
	}
	std::string name() const override { return m_inner->name() + " | fixed ego"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override
	{
		std::vector<Eigen::VectorXd> all;
		size_t j = 0;
		for (const auto& k : m_inner->keys()) all.push_back(k == m_fixed ? m_value : x[j++]);
		TLinearization L = m_inner->linearize(all);
		std::vector<Eigen::MatrixXd> J;
		for (size_t i = 0; i < m_inner->keys().size(); ++i)
			if (!(m_inner->keys()[i] == m_fixed)) J.push_back(L.J[i]);
		L.J = std::move(J);
		return L;
	}

private:
	static std::vector<TVarKey> others(const CTerm& t, const TVarKey& fixed)
	{
		std::vector<TVarKey> k;
		for (const auto& key : t.keys())
			if (!(key == fixed)) k.push_back(key);
		return k;
	}
	CTermPtr m_inner;
	TVarKey m_fixed;
	Eigen::VectorXd m_value;
};
}  // namespace

void CAlg1Backend::addTerm(const CTermPtr& t)
{
	if (m_anchorPending && t->touches(m_ego))
		m_cost.addTerm(std::make_shared<CConditionedTerm>(t, m_ego, m_fixedEgo));
	else
		m_cost.addTerm(t);
}

// prior_gauge = anchor: x_{t-1} is exact, so the marginal of x_t is N(x_{t-1} (+) u, G Sigma_u
// G^T), the limit of the prior filter's step as Sigma_0 -> 0 (the EKF's P = F 0 F^T + Q).
void CAlg1Backend::propagateAnchored(const Eigen::Vector3d& u, const Eigen::Matrix3d& Su)
{
	Eigen::Matrix3d F, G;
	const Eigen::Vector3d pred = models::composePose(m_fixedEgo, u, &F, &G);
	m_ego = TVarKey::ego(m_step);
	m_fixedEgo = pred;
	if (Su.isZero(0)) return;  // still exact
	if (Eigen::LLT<Eigen::Matrix3d>(Su).info() != Eigen::Success)
		throw std::runtime_error(
		    "CAlg1Backend: the odometry covariance is singular but not zero; the framework "
		    "needs it positive definite (or exactly zero)");
	// The ego is independent of everything estimated so far (its past value was exact).
	m_cost.addVariable(m_ego, pred);
	m_cost.addTerm(CPriorTerm::fromCovariance({m_ego}, {3}, pred, G * Su * G.transpose()));
	m_anchorPending = false;
}

// Alg. 5 (tracked landmarks), then Alg. 3 (new ones): GN steps (Theorems A.3, A.1).
void CAlg1Backend::staticSteps(const estimator::TRoutedStep& in)
{
	const auto& mo = m_opts.model;
	const auto tracked = estimator::readingsOf(in.with(estimator::Route::StaticKnown));
	const auto fresh = estimator::readingsOf(in.with(estimator::Route::StaticNew));
	if (!tracked.empty())
	{
		for (const auto& m : tracked)
			addTerm(std::make_shared<CMeasurementTerm>(m_ego.step, TVarKey::landmark(m.id), m.z,
			                                           mo.measurement_model, mo.Sigma_v, m_sensor));
		const auto r = gnAndCollapse();
		m_report.static_updates = tracked.size();
		m_report.nis_static = r.cost_linear_min;
		m_report.nis_static_dof = 2 * tracked.size();
	}
	if (!fresh.empty())
	{
		const Eigen::Vector3d x = egoValue();
		for (const auto& m : fresh)
		{
			const TVarKey k = TVarKey::landmark(m.id);
			m_cost.addVariable(
			    k, models::inverseObserveFromSensor(mo.measurement_model, x, m_sensor, m.z));
			addTerm(std::make_shared<CMeasurementTerm>(m_ego.step, k, m.z, mo.measurement_model,
			                                           mo.Sigma_v, m_sensor));
		}
		gnAndCollapse();
		m_report.static_new = fresh.size();
	}
	for (const auto& m : in.statics()) m_drop.noteSeen(m.reading.id, m_step);
}

// Alg. 3 for object features (time 0 of new objects, time t of known ones).
void CAlg1Backend::objectFeatureAugmentation(const estimator::TRoutedStep& in)
{
	m_newTimeT.clear();
	const auto& mo = m_opts.model;
	std::set<int32_t> seenObjects;  // objects read now (unknown features included)
	for (const auto& m : in.readings)
		if (m.object >= 0) seenObjects.insert(m.object);
	if (seenObjects.empty()) return;
	const auto objects = in.objects();
	std::vector<TVarKey> stale;
	for (const auto& k : m_cost.keys())
		if (isTimeT(k) && seenObjects.count(k.id)) stale.push_back(k);
	if (!stale.empty())
	{
		m_report.dropped_time_t += stale.size();
		m_cost.marginalize(stale);
	}
	const Eigen::Vector3d x = egoValue();
	size_t added = 0;
	for (const auto& m : objects)
	{
		if (hasVelocity(m.object)) continue;  // its readings were updates (objectFeatureUpdates)
		++added;
		const TVarKey k = TVarKey::objectFeature(m.object, m.feature, m_step);
		if (m.route == estimator::Route::ObjectFirstSighting)
			++m_report.object_features_new;
		else
		{
			++m_report.object_features_t;
			m_newTimeT.push_back(k);
		}
		m_cost.addVariable(
		    k, models::inverseObserveFromSensor(mo.measurement_model, x, m_sensor, m.reading.z));
		addTerm(std::make_shared<CMeasurementTerm>(m_ego.step, k, m.reading.z, mo.measurement_model,
		                                           mo.Sigma_v, m_sensor));
	}
	if (added > 0) gnAndCollapse();
}

// Alg. 4 per object as a GN step (Theorem 4.1).
void CAlg1Backend::objectPoseAugmentation()
{
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		TObjectPoseKeys k;
		const PoseStep r = addObjectPose(m_cost, obj, o.first_step, o.feature_index, m_newTimeT,
		                                 m_step, m_opts.pose_residual == PoseResidual::PoseSpace,
		                                 m_opts.model.Sigma_xi, k);
		if (r == PoseStep::NotSeen) continue;
		if (r == PoseStep::Degenerate)
		{
			++m_report.skipped_pose_degenerate;
			continue;
		}
		gnAndCollapse();
		++m_report.object_poses_added;
	}
}

// The object motion model (Alg. 6: smoothing) per object as a GN step (Theorem 4.2).
void CAlg1Backend::objectMotion()
{
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		std::vector<int> steps;
		for (const auto& k : m_cost.keys())
			if (k.kind == VarKind::ObjectPose && k.id == obj) steps.push_back(k.step);
		std::sort(steps.begin(), steps.end());
		for (const auto& pm : m_motion->select(obj, m_step, steps, o.poseDim()))
		{
			m_cost.addTerm(std::make_shared<CMotionModelTerm>(m_motion, pm));
			gnAndCollapse();
			++m_report.smoothing_updates;
		}
	}
}

// The drop policies: removing blocks from (mu, Sigma) is marginalization.
void CAlg1Backend::drops()
{
	std::vector<TVarKey> M;
	if (m_drop.dropTimeT())
		for (const auto& k : m_cost.keys())
			if (isTimeT(k))
			{
				M.push_back(k);
				++m_report.dropped_time_t;
			}
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		std::vector<TVarKey> poses;
		for (const auto& k : m_cost.keys())
			if (k.kind == VarKind::ObjectPose && k.id == obj) poses.push_back(k);
		std::sort(poses.begin(), poses.end());
		const size_t nd = m_drop.posesToDrop(poses.size());
		for (size_t i = 0; i < nd; ++i)
		{
			TObjectPoseEstimate e;
			e.step = poses[i].step;
			e.mean = m_cost.value(poses[i]);
			e.cov = marginalCov(poses[i]);
			m_router->registry().recordDroppedPose(obj, toRecord(e), m_drop.record());
			M.push_back(poses[i]);
			++m_report.dropped_poses;
		}
	}
	for (const auto& k : m_cost.keys())
	{
		if (k.kind != VarKind::StaticLandmark) continue;
		const bool unseen = m_drop.staticDue(k.id, m_step, k.step);
		if (!unseen && !m_drop.pruneDue(k.id, m_step, k.step)) continue;
		TStaticLandmarkEstimate e;
		e.id = k.id;
		e.mean = m_cost.value(k);
		e.cov = marginalCov(k);
		e.in_state = false;
		if (m_drop.record()) m_droppedStatic.push_back(e);
		m_drop.forget(k.id);
		M.push_back(k);
		++(unseen ? m_report.dropped_static : m_report.pruned_static);
	}
	if (!M.empty()) m_cost.marginalize(M);
}

}  // namespace dynslam::framework
