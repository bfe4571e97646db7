#include <dynslam/common/backend_results.h>
#include <dynslam/common/seam_options.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/framework/CWindowBackend.h>
#include <dynslam/framework/object_pose_step.h>

#include <algorithm>
#include <set>
#include <stdexcept>

namespace dynslam::framework
{
CWindowBackend::CWindowBackend(const TBackendOptions& opts) : m_opts(opts)
{
	if (m_opts.backend == "alg1")
		throw std::invalid_argument("CWindowBackend: use CAlg1Backend for backend = alg1");
	m_opts.validate();
	reset();
}

bool CWindowBackend::coupled() const { return m_opts.backend.rfind("clusterslam", 0) != 0; }

void CWindowBackend::reset()
{
	m_cost = CRunningCost();
	m_objCost = CRunningCost();
	m_egoLink.reset();
	m_step = -1;
	m_router = estimator::routers().make("ids", {});
	if (!estimator::objectMotionModels().caps(m_opts.model.object_model).window)
		throw std::invalid_argument("[DynamicKFSLAM] object_model = " + m_opts.model.object_model +
		                            ": not implemented in the windowed back-end "
		                            "(the dynamic EKF only, issue 13)");
	m_motion = estimator::objectMotionModels().make(m_opts.model.object_model,
	                                                objectMotionParams(m_opts.model));
	m_drop = estimator::CDropPolicy(m_opts.model.dropOptions());
	m_body.clear();
	m_droppedStatic.clear();
	m_egoRecorded.clear();
	m_report = TStepReport();
}

std::map<int, Eigen::Vector3d> CWindowBackend::finalTrajectory() const
{
	std::map<int, Eigen::Vector3d> out = m_egoRecorded;
	for (const auto& k : m_cost.keys())
		if (k.kind == VarKind::EgoPose) out[k.step] = m_cost.value(k);
	return out;
}

TGaussNewtonOptions CWindowBackend::gnOptions() const
{
	TGaussNewtonOptions o;
	o.solver = m_opts.solver == 1 ? SolverKind::Dense
	                              : (m_opts.solver == 2 ? SolverKind::Sparse : SolverKind::Auto);
	o.compute_covariance = false;
	return o;
}

Eigen::Matrix2d CWindowBackend::pointCov(const Eigen::Vector2d& z) const
{
	if (m_opts.model.measurement_model == models::MeasurementModel::Cartesian)
		return m_opts.model.Sigma_v;
	Eigen::Matrix2d J;
	models::rangeBearingToCartesian(z, &J);
	return J * m_opts.model.Sigma_v * J.transpose();
}

void CWindowBackend::processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
                                              const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	const auto& mo = m_opts.model;
	static const std::string who = "CWindowBackend";
	const estimator::TStepInput in = parseStepInput(action, SF, mo.parseOptions(), who);
	m_router->validate(in.readings, who);
	++m_step;
	m_sensor = in.sensor_pose;
	m_report = TStepReport();
	m_report.step = m_step;
	const estimator::TRoutedStep routed = m_router->route(
	    m_step, in.readings, [this](int32_t id) { return m_cost.has(TVarKey::landmark(id)); });
	m_report.skipped_unknown_object_feature = routed.skipped_unknown_object_feature;
	m_report.skipped_unknown_id = routed.skipped_unknown_id;  // ID -1: no association here
	const TVarKey ego = TVarKey::ego(m_step);
	const Eigen::Matrix3d Su = mo.motion_noise_from_action ? in.U : mo.Sigma_w;
	// 1. ego pose: prior (first step) or odometry residual
	if (m_step == 0)
	{
		Eigen::Matrix3d G;
		const Eigen::Vector3d x0 = models::composePose(mo.initial_pose, in.u, nullptr, &G);
		m_cost.addVariable(ego, x0);
		m_cost.addTerm(
		    CPriorTerm::fromCovariance({ego}, {3}, x0, mo.Sigma_0 + G * Su * G.transpose()));
	}
	else
	{
		const TVarKey prev = TVarKey::ego(m_step - 1);
		m_cost.addVariable(ego, models::composePose(m_cost.value(prev), in.u));
		m_cost.addTerm(std::make_shared<COdometryTerm>(m_step - 1, m_step, in.u, Su));
	}
	// 2. static landmarks
	for (const auto& r : routed.statics())
	{
		const estimator::TReading& m = r.reading;
		const TVarKey k = TVarKey::landmark(m.id);
		if (r.route == estimator::Route::StaticNew)
		{
			m_cost.addVariable(k, models::inverseObserveFromSensor(
			                          mo.measurement_model, m_cost.value(ego), m_sensor, m.z));
			++m_report.static_new;
		}
		else
			++m_report.static_updates;
		m_cost.addTerm(std::make_shared<CMeasurementTerm>(m_step, k, m.z, mo.measurement_model,
		                                                  mo.Sigma_v, m_sensor));
		m_drop.noteSeen(m.id, m_step);
	}
	// 3. objects
	if (!coupled())
	{
		optimize(m_cost);
		m_objCost.addVariable(ego, m_cost.value(ego));
		linkEgoToObjectCost();
	}
	if (cube())
		addCubeObjects(routed, ego);
	else
		addObjects(routed, ego);
	if (!coupled()) linkEgoToObjectCost();
	optimize(objectCost());
	// 4. time-t features (dynaslam2, clusterslam): marginalize or drop right away
	if (!cube() && m_opts.object_features != TBackendOptions::FeaturePolicy::Keep)
	{
		std::vector<TVarKey> ft;
		for (const auto& k : objectCost().keys())
			if (k.kind == VarKind::ObjectFeature && k.step == m_step &&
			    m_router->registry().isTimeT(k.id, m_step))
				ft.push_back(k);
		if (!ft.empty())
		{
			if (m_opts.object_features == TBackendOptions::FeaturePolicy::Drop)
				objectCost().drop(ft);
			else
				objectCost().marginalize(ft);
			m_report.dropped_time_t += ft.size();
		}
	}
	slideWindow();
}

void CWindowBackend::optimize(CRunningCost& c)
{
	m_lastIterations = 0;
	for (int it = 0; it < m_opts.max_iterations; ++it)
	{
		const auto r = c.gaussNewtonStep(gnOptions());
		++m_lastIterations;
		if (r.max_step < m_opts.tolerance) break;
	}
}

void CWindowBackend::linkEgoToObjectCost()
{
	if (m_egoLink) m_objCost.removeTerm(m_egoLink);
	std::vector<TVarKey> keys;
	std::vector<int> dims;
	for (const auto& k : m_objCost.keys())
		if (k.kind == VarKind::EgoPose)
		{
			keys.push_back(k);
			dims.push_back(3);
			m_objCost.setValue(k, m_cost.value(k));
		}
	if (keys.empty()) return;
	Eigen::VectorXd mean(3 * keys.size());
	for (size_t i = 0; i < keys.size(); ++i) mean.segment<3>(3 * i) = m_cost.value(keys[i]);
	Eigen::MatrixXd C;
	if (m_opts.backend == "clusterslam_semidecoupled")
		C = m_cost.covariance(keys, gnOptions());  // one-way coupling: the static marginal
	else
		C = Eigen::MatrixXd::Identity(3 * keys.size(), 3 * keys.size()) * 1e-12;  // held fixed
	auto p = CPriorTerm::fromCovariance(keys, dims, mean, C);
	m_objCost.addTerm(p);
	m_egoLink = p;
}

void CWindowBackend::addObjects(const estimator::TRoutedStep& in, const TVarKey& ego)
{
	const auto& mo = m_opts.model;
	CRunningCost& c = objectCost();
	const Eigen::Vector3d x = c.value(ego);
	std::vector<TVarKey> newT;
	for (const auto& r : in.objects())
	{
		const TVarKey k = TVarKey::objectFeature(r.object, r.feature, m_step);
		if (r.route == estimator::Route::ObjectFirstSighting)
			++m_report.object_features_new;
		else
		{
			newT.push_back(k);
			++m_report.object_features_t;
		}
		c.addVariable(
		    k, models::inverseObserveFromSensor(mo.measurement_model, x, m_sensor, r.reading.z));
		c.addTerm(std::make_shared<CMeasurementTerm>(m_step, k, r.reading.z, mo.measurement_model,
		                                             mo.Sigma_v, m_sensor));
	}
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		TObjectPoseKeys k;
		const PoseStep r =
		    addObjectPose(c, obj, o.first_step, o.feature_index, newT, m_step,
		                  m_opts.pose_residual == PoseResidual::PoseSpace, mo.Sigma_xi, k);
		if (r == PoseStep::NotSeen) continue;
		if (r == PoseStep::Degenerate)
		{
			++m_report.skipped_pose_degenerate;
			continue;
		}
		++m_report.object_poses_added;
		// The object motion model (Alg. 6: smoothing) on the poses in the window.
		std::vector<int> steps;
		for (const auto& key : c.keys())
			if (key.kind == VarKind::ObjectPose && key.id == obj) steps.push_back(key.step);
		std::sort(steps.begin(), steps.end());
		for (const auto& pm : m_motion->select(obj, m_step, steps, c.dim(k.pose)))
		{
			c.addTerm(std::make_shared<CMotionModelTerm>(m_motion, pm));
			++m_report.smoothing_updates;
		}
	}
}

namespace
{
/** The CubeSLAM-like measurement of an object's body pose from the features seen now (points
 * `pts` with covariances `covs`, `seen` their index in `body`): T = (c0 + xi_t, xi_theta) with
 * its covariance Gamma2 diag(covs) Gamma2^T, or the point itself for a one-feature object.
 * False if the rotation is undetermined. */
bool fitBodyPose(const Eigen::Matrix2Xd& body, const std::vector<int>& seen,
                 const std::vector<Eigen::Vector2d>& pts, const std::vector<Eigen::Matrix2d>& covs,
                 Eigen::VectorXd& T, Eigen::MatrixXd& ST)
{
	const size_t m = pts.size();
	if (body.cols() == 1)
	{
		T = pts[0];
		ST = covs[0];
		return true;
	}
	Eigen::Matrix2Xd zt(2, m);
	for (size_t i = 0; i < m; ++i) zt.col(Eigen::Index(i)) = pts[i];
	Eigen::MatrixXd G1, G2;
	Eigen::Vector3d xi;
	try
	{
		xi = models::objectPoseInverse(body, zt, seen, &G1, &G2);
	}
	catch (const std::domain_error&)
	{
		return false;
	}
	const Eigen::Vector2d c0 = body.rowwise().mean();
	T = Eigen::Vector3d(c0[0] + xi[0], c0[1] + xi[1], xi[2]);
	ST = Eigen::MatrixXd::Zero(3, 3);
	for (size_t i = 0; i < m; ++i)
		ST += G2.middleCols(2 * i, 2) * covs[i] * G2.middleCols(2 * i, 2).transpose();
	return true;
}
}  // namespace

void CWindowBackend::addCubeObjects(const estimator::TRoutedStep& in, const TVarKey& ego)
{
	CRunningCost& c = objectCost();
	const Eigen::Vector3d x = c.value(ego);
	// Group this step's used measurements per object, as robot-frame points p = s (+) p_sensor
	// with their covariances (the sensor's pose s on the robot, Sigma rotated by its yaw).
	struct TPoint
	{
		int32_t id;
		Eigen::Vector2d p;
		Eigen::Matrix2d cov;
	};
	std::map<int32_t, std::vector<TPoint>> per;
	const Eigen::Matrix2d Rs = models::rot2(m_sensor[2]);
	for (const auto& r : in.objects())
	{
		const Eigen::Vector2d p =
		    m_opts.model.measurement_model == models::MeasurementModel::Cartesian
		        ? r.reading.z
		        : models::rangeBearingToCartesian(r.reading.z);
		per[r.object].push_back({r.reading.id, m_sensor.head<2>() + Rs * p,
		                         Rs * pointCov(r.reading.z) * Rs.transpose()});
	}
	for (const auto& [obj, meas] : per)
	{
		const estimator::TObjectEntry& o = m_router->registry().at(obj);
		const bool first = o.first_step == m_step;
		std::vector<int> seen;
		std::vector<Eigen::Vector2d> pts;
		std::vector<Eigen::Matrix2d> covs;
		if (first)
		{
			// The time-0 features, in the registry's (observation) order.
			Eigen::Matrix2Xd& body = m_body[obj];
			body.resize(2, Eigen::Index(meas.size()));
			for (size_t i = 0; i < meas.size(); ++i) body.col(Eigen::Index(i)) = meas[i].p;
			m_report.object_features_new += meas.size();
		}
		const Eigen::Matrix2Xd& body = m_body.at(obj);
		for (const TPoint& q : meas)
		{
			seen.push_back(o.indexOf(q.id));
			pts.push_back(q.p);
			covs.push_back(q.cov);
		}
		const size_t n = o.feature_ids.size(), m = pts.size();
		if (m == 0) continue;
		if (n >= 2 && m < 2)
		{
			++m_report.skipped_pose_degenerate;
			continue;
		}
		Eigen::VectorXd T;
		Eigen::MatrixXd ST;
		if (!fitBodyPose(body, seen, pts, covs, T, ST))
		{
			++m_report.skipped_pose_degenerate;
			continue;
		}
		const TVarKey k = TVarKey::objectBodyPose(obj, m_step);
		Eigen::VectorXd init(T.size());
		init.head<2>() = models::cartesianInverse(x, T.head<2>());
		if (T.size() == 3) init[2] = models::wrapToPi(x[2] + T[2]);
		c.addVariable(k, init);
		c.addTerm(std::make_shared<CBodyPoseMeasurementTerm>(m_step, k, T, ST));
		if (!first) ++m_report.object_poses_added;
	}
}

TObjectPoseEstimate CWindowBackend::poseEstimate(int32_t obj, int step) const
{
	const CRunningCost& c = objectCost();
	TObjectPoseEstimate e;
	e.step = step;
	e.in_state = true;
	if (!cube())
	{
		const TVarKey k = TVarKey::objectPose(obj, step);
		e.mean = c.value(k);
		e.cov = c.covariance({k}, gnOptions());
		return e;
	}
	const estimator::TObjectEntry& o = m_router->registry().at(obj);
	const TVarKey k0 = TVarKey::objectBodyPose(obj, o.first_step),
	              kt = TVarKey::objectBodyPose(obj, step);
	const Eigen::VectorXd a = c.value(k0), b = c.value(kt);
	const Eigen::Index d = a.size();
	e.mean = blockMinus(VarKind::ObjectBodyPose, b, a);
	const Eigen::MatrixXd C = c.covariance({k0, kt}, gnOptions());
	Eigen::MatrixXd J(d, 2 * d);
	J << -Eigen::MatrixXd::Identity(d, d), Eigen::MatrixXd::Identity(d, d);
	e.cov = J * C * J.transpose();
	return e;
}

void CWindowBackend::slideWindow()
{
	if (m_opts.window_size < 0) return;
	const int oldest = m_step - m_opts.window_size + 1;
	const TVarKey old = TVarKey::ego(oldest - 1);
	if (oldest - 1 < 0 || !m_cost.has(old)) return;
	m_egoRecorded[old.step] = m_cost.value(old);
	// Object poses of that step leave with it (recorded with their last estimate).
	CRunningCost& oc = objectCost();
	std::vector<TVarKey> M;
	for (const auto& [obj, o] : m_router->registry().objects())
	{
		const TVarKey pk = cube() ? TVarKey::objectBodyPose(obj, oldest - 1)
		                          : TVarKey::objectPose(obj, oldest - 1);
		if (!oc.has(pk) || (cube() && oldest - 1 == o.first_step)) continue;
		m_router->registry().recordDroppedPose(obj, toRecord(poseEstimate(obj, oldest - 1)),
		                                       m_drop.record());
		M.push_back(pk);
		++m_report.dropped_poses;
	}
	if (coupled())
	{
		M.push_back(old);
		m_cost.marginalize(M);
		return;
	}
	// Separate costs: the object cost's ego copy keeps its static prior while it leaves.
	if (m_objCost.has(old)) M.push_back(old);
	if (!M.empty())
	{
		m_objCost.marginalize(M);  // folds the current ego link into a prior
		m_egoLink.reset();
	}
	m_cost.marginalize({old});
}
}  // namespace dynslam::framework
