#include <dynslam/backend_results.h>
#include <dynslam/framework/CAlg1Backend.h>
#include <dynslam/framework/object_pose_step.h>
#include <dynslam/models/object_pose.h>
#include <dynslam/models/se2.h>
#include <dynslam/step_input.h>

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
	m_cost.addVariable(m_ego, m_opts.model.initial_pose);
	m_cost.addTerm(
	    CPriorTerm::fromCovariance({m_ego}, {3}, m_opts.model.initial_pose, m_opts.model.Sigma_0));
	m_step = -1;
	if (!m_userRouter) m_router = estimator::makeRouter("ids");
	m_router->reset();
	if (!m_userMotion && m_opts.model.objectCentric())
		m_motion = makeObjectCentricModel(m_opts.model);
	else if (!m_userMotion)
		m_motion = estimator::makeObjectMotionModel(m_opts.model.smoothing, m_opts.model.Sigma_s);
	m_velocitySince.clear();
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
	propagate(in);                      // Alg. 7 / Theorem A.5
	predictObjects();                   // object-centric models only (cv, ctrv)
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
	if (m_opts.model.skip_prediction_on_empty_map && m_cost.numVariables() == 1) return;
	const Eigen::Matrix3d Su = m_opts.model.motion_noise_from_action ? in.U : m_opts.model.Sigma_w;
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

// Alg. 5 (tracked landmarks), then Alg. 3 (new ones): GN steps (Theorems A.3, A.1).
void CAlg1Backend::staticSteps(const estimator::TRoutedStep& in)
{
	const auto& mo = m_opts.model;
	const auto tracked = estimator::readingsOf(in.with(estimator::Route::StaticKnown));
	const auto fresh = estimator::readingsOf(in.with(estimator::Route::StaticNew));
	if (!tracked.empty())
	{
		for (const auto& m : tracked)
			m_cost.addTerm(std::make_shared<CMeasurementTerm>(m_ego.step, TVarKey::landmark(m.id),
			                                                  m.z, mo.measurement_model, mo.Sigma_v,
			                                                  m_sensor));
		const auto r = gnAndCollapse();
		m_report.static_updates = tracked.size();
		m_report.nis_static = r.cost_linear_min;
		m_report.nis_static_dof = 2 * tracked.size();
	}
	if (!fresh.empty())
	{
		const Eigen::Vector3d x = m_cost.value(m_ego);
		for (const auto& m : fresh)
		{
			const TVarKey k = TVarKey::landmark(m.id);
			m_cost.addVariable(
			    k, models::inverseObserveFromSensor(mo.measurement_model, x, m_sensor, m.z));
			m_cost.addTerm(std::make_shared<CMeasurementTerm>(
			    m_ego.step, k, m.z, mo.measurement_model, mo.Sigma_v, m_sensor));
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
	const Eigen::Vector3d x = m_cost.value(m_ego);
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
		m_cost.addTerm(std::make_shared<CMeasurementTerm>(
		    m_ego.step, k, m.reading.z, mo.measurement_model, mo.Sigma_v, m_sensor));
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
		if (k.kind != VarKind::StaticLandmark || !m_drop.staticDue(k.id, m_step, k.step)) continue;
		TStaticLandmarkEstimate e;
		e.id = k.id;
		e.mean = m_cost.value(k);
		e.cov = marginalCov(k);
		e.in_state = false;
		if (m_drop.record()) m_droppedStatic.push_back(e);
		m_drop.forget(k.id);
		M.push_back(k);
		++m_report.dropped_static;
	}
	if (!M.empty()) m_cost.marginalize(M);
}

// ------------------------------------------------------------------------------------------
// Results
// ------------------------------------------------------------------------------------------
mrpt::poses::CPosePDFGaussian CAlg1Backend::getEgoPose() const
{
	mrpt::poses::CPosePDFGaussian p;
	const Eigen::Vector3d x = m_cost.value(m_ego);
	p.mean = mrpt::poses::CPose2D(x[0], x[1], x[2]);
	p.cov = mrpt::math::CMatrixDouble33(Eigen::Matrix3d(marginalCov(m_ego)));
	return p;
}

std::vector<TStaticLandmarkEstimate> CAlg1Backend::getStaticLandmarks(bool includeDropped) const
{
	std::vector<TStaticLandmarkEstimate> out;
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::StaticLandmark)
		{
			TStaticLandmarkEstimate e;
			e.id = k.id;
			e.mean = m_cost.value(k);
			e.cov = marginalCov(k);
			out.push_back(e);
		}
	if (includeDropped) out.insert(out.end(), m_droppedStatic.begin(), m_droppedStatic.end());
	return out;
}

std::vector<TObjectFeatureEstimate> CAlg1Backend::getObjectFeatures() const
{
	std::vector<TObjectFeatureEstimate> out;
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::ObjectFeature)
		{
			TObjectFeatureEstimate e;
			e.object = k.id;
			e.feature = k.feature;
			e.id = m_router->featureId(k.id, k.feature);
			e.at_time0 = !isTimeT(k);
			e.step = k.step;
			e.mean = m_cost.value(k);
			e.cov = marginalCov(k);
			out.push_back(e);
		}
	return out;
}

std::map<int32_t, TObjectTrack> CAlg1Backend::getObjectTracks() const
{
	std::map<int32_t, TObjectTrack> out = tracksFromRegistry(m_router->registry());
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::ObjectPose)
		{
			TObjectPoseEstimate e;
			e.step = k.step;
			e.mean = m_cost.value(k);
			e.cov = marginalCov(k);
			if (const TVarKey v = TVarKey::objectVelocity(k.id, k.step); m_cost.has(v))
			{
				e.velocity = m_cost.value(v);
				e.velocity_cov = marginalCov(v);
			}
			e.in_state = true;
			out[k.id].poses.push_back(e);
		}
	sortTrackPoses(out);
	return out;
}

void CAlg1Backend::getLabelledState(Eigen::VectorXd& x, Eigen::MatrixXd& P,
                                    std::vector<std::string>& labels) const
{
	TGaussNewtonOptions o;
	o.solver = SolverKind::Dense;
	x = m_cost.stackedValues();
	P = m_cost.covariance(m_cost.keys(), o);
	labels.clear();
	for (const auto& k : m_cost.keys())
	{
		const std::string ob = "obj" + std::to_string(k.id);
		switch (k.kind)
		{
			case VarKind::EgoPose:
				labels.insert(labels.end(), {"ego.x", "ego.y", "ego.theta"});
				break;
			case VarKind::StaticLandmark:
				labels.push_back("lm" + std::to_string(k.id) + ".x");
				labels.push_back("lm" + std::to_string(k.id) + ".y");
				break;
			case VarKind::ObjectFeature:
			{
				const std::string f = ob + ".f" + std::to_string(k.feature) +
				                      (isTimeT(k) ? ".t" + std::to_string(k.step) : ".t0");
				labels.push_back(f + ".x");
				labels.push_back(f + ".y");
				break;
			}
			case VarKind::ObjectPose:
			case VarKind::ObjectBodyPose:
			{
				const std::string p = ob + ".xi" + std::to_string(k.step);
				labels.push_back(p + ".dx");
				labels.push_back(p + ".dy");
				if (m_cost.dim(k) == 3) labels.push_back(p + ".dtheta");
				break;
			}
			case VarKind::ObjectVelocity:  // the EKF's label: the step the velocity was added
				for (int i = 0; i < m_cost.dim(k); ++i)
					labels.push_back(ob + ".v" + std::to_string(m_velocitySince.at(k.id)) + "." +
					                 std::to_string(i));
				break;
		}
	}
}
}  // namespace dynslam::framework
