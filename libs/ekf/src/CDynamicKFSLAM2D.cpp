/** CDynamicKFSLAM2D: the step driver on the estimator core (parse -> route -> propagate ->
 * update -> augment -> motion model -> drop -> commit), the prediction (Alg. 7), the static
 * update through the update engine (Alg. 5). The capability modules' hooks: src/modules/
 * (doc/architecture.md "Capability modules"). MRPT's hooks: CDynamicKFSLAM2D_mrpt.cpp, their
 * bodies and MRPT's update engine src/mrpt_kalman_adapter.cpp. The state's lifecycle:
 * src/state_store.cpp; the router's context and the box tracks: src/router_context.cpp; the
 * state surgeries: src/modules/state_surgery.cpp. Augmentations, drops and the object motion
 * model: CDynamicKFSLAM2D_objects.cpp. */
#include <dynslam/common/seam_options.h>
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/ekf/CMrptUpdateEngine.h>
#include <dynslam/ekf/ekf_registries.h>
#include <dynslam/ekf/slam_services.h>
#include <dynslam/estimator/state_helper.h>
#include <mrpt/system/string_utils.h>

#include <limits>
#include <set>
#include <stdexcept>

#include "gauge/prior_gauge.h"
#include "modules/first_estimates.h"
#include "modules/fusion.h"
#include "modules/module_list.h"
#include "modules/object_motion.h"
#include "modules/odometry_bias.h"
#include "modules/state_surgery.h"
#include "mrpt_kalman_adapter.h"
#include "router_context.h"
#include "state_store.h"

namespace dynslam
{
const char* toString(SlotKind k)
{
	switch (k)
	{
		case SlotKind::StaticLandmark:
			return "static_landmark";
		case SlotKind::ObjectFeature0:
			return "object_feature_t0";
		case SlotKind::ObjectFeatureT:
			return "object_feature_t";
		case SlotKind::ObjectPoseA:
			return "object_pose_a";
		case SlotKind::ObjectPoseB:
			return "object_pose_b";
		case SlotKind::ObjectVelocityA:
			return "object_velocity_a";
		case SlotKind::ObjectVelocityB:
			return "object_velocity_b";
		case SlotKind::OdometryBias:
			return "odometry_bias";
		case SlotKind::Compressed:
			return "compressed";
	}
	return "?";
}

CDynamicKFSLAM2D::CDynamicKFSLAM2D()
    : m_gauge(std::make_unique<ekf::CPriorGauge>(options)),
      m_store(std::make_unique<ekf::CStateStore>()),
      m_mrpt(std::make_unique<ekf::CMrptKalmanAdapter>(*this))
{
	setLoggerName("CDynamicKFSLAM2D");
	reset();
}

CDynamicKFSLAM2D::~CDynamicKFSLAM2D() = default;

void CDynamicKFSLAM2D::setRouter(std::unique_ptr<estimator::IMeasurementRouter> r)
{
	if (!r) throw std::invalid_argument("CDynamicKFSLAM2D::setRouter: null");
	m_router = std::move(r);
	m_userRouter = true;
}

void CDynamicKFSLAM2D::setUpdateEngine(std::unique_ptr<estimator::IUpdateEngine> e)
{
	if (!e) throw std::invalid_argument("CDynamicKFSLAM2D::setUpdateEngine: null");
	m_engine = std::move(e);
	m_userEngine = true;
}

void CDynamicKFSLAM2D::setStateLifecycle(std::unique_ptr<estimator::IStateLifecycle> l)
{
	if (!l) throw std::invalid_argument("CDynamicKFSLAM2D::setStateLifecycle: null");
	m_lifecycle = std::move(l);
	m_userLifecycle = true;
}

void CDynamicKFSLAM2D::setObjectMotionModel(std::unique_ptr<estimator::IObjectMotionModel> m)
{
	if (!m) throw std::invalid_argument("CDynamicKFSLAM2D::setObjectMotionModel: null");
	m_motion = std::move(m);
	m_userMotion = true;
}

void CDynamicKFSLAM2D::makeSeams()
{
	// The seams: the options' implementations (their registries, seam_options.h) unless another
	// one was set. The motion model first: its capabilities shape the router's.
	if (!m_userMotion)
		m_motion =
		    estimator::objectMotionModels().make(options.object_model, objectMotionParams(options));
	m_motion->resetObjectState();  // per-object state of the rule (a user model too)
	const bool objectCentric = m_motion->objectCentric();
	if (!m_userRouter)
	{
		// Late joining gives a joiner an f_0 from the paper model's pose; object-centric models
		// (cv, ctrv) keep body-frame features of a fixed set: no joining there.
		estimator::TClassifyParams classify = options.classify;
		classify.join = classify.join && !objectCentric;
		// A merge needs the lost object predicted across the gap (doc/results/classification.md
		// "Merging a linked object"): object-centric models only.
		classify.merge_linked = classify.merge_linked && objectCentric;
		m_router =
		    estimator::routers().make(options.feature_labels, {&classify, &options.boxes.params});
		// ID -1 readings associated with MRPT's data association (as CRangeBearingKFSLAM2D).
		m_router->setStaticAssociation(slamStaticAssociation(options.classify.assoc));
	}
	m_router->reset();
	if (!m_userEngine && !options.sparse_static_update)
		m_engine = std::make_unique<CMrptUpdateEngine>(*this);  // static_update = mrpt
	else if (!m_userEngine)
		m_engine = ekfUpdateEngines().make(options.outlier_method, updateEngineParams(options));
	// The gate threshold goes to the engine unless the method has none (outlier_method = none).
	m_engineGated = ekfUpdateEngines().caps(options.outlier_method).gate;
	if (!m_userLifecycle)
		m_lifecycle = estimator::stateLifecycles().make(stateLifecycleName(options),
		                                                lifecycleParams(options));
	if (m_lifecycle->rewritesStorage() && !m_engine->updatesGivenState())
		throw std::invalid_argument("CDynamicKFSLAM2D: the state lifecycle " + m_lifecycle->name() +
		                            " cannot be combined with the update engine " +
		                            m_engine->name() +
		                            " (it works on the filter's own storage, not on the state "
		                            "it is given)");
}

void CDynamicKFSLAM2D::reset()
{
	m_xkk.resize(3);
	for (int i = 0; i < 3; ++i) m_xkk[i] = options.initial_pose[i];
	m_cov.resize(3);
	// prior_gauge = anchor: x_0 is the gauge; Sigma_0 enters only the reported covariances.
	cov() = m_gauge->reset();
	makeSeams();
	m_drop = estimator::CDropPolicy(options.dropOptions());
	// The capability modules the options enable (src/modules/module_list.cpp).
	if (!m_modules) m_modules = std::make_unique<ekf::CModuleList>();
	ekf::TFilterAccess access{*this};
	m_modules->build(access);
	m_lifecycle->reset();
	m_store->reset(m_lifecycle->rewritesStorage());
	m_layout.clear();
	if (ekf::COdometryBiasModule* bias = m_modules->odometryBias()) bias->addBlock(access);
	onLayoutChanged();
	m_droppedStatic.clear();
	m_in = estimator::TStepInput();
	m_routed = estimator::TRoutedStep();
	m_step = -1;
	m_report = TStepReport();
	m_failed = false;
	m_lastF.reset();
}

void CDynamicKFSLAM2D::loadOptions(const mrpt::config::CConfigFileBase& ini,
                                   const std::string& section)
{
	options.loadFromConfigFile(ini, section);
	// Check `method` before MRPT parses it: MRPT's read_enum casts any value that starts with a
	// digit to TKFMethod without a range check (undefined behaviour for e.g. "5"; found by
	// fuzzing under UBSan).
	const std::string kf = section + "_KalmanFilter";
	const std::string method = mrpt::system::trim(ini.read_string(kf, "method", "kfEKFNaive"));
	if (method != "kfEKFNaive" && method != "kfEKFAlaDavison" && method != "0" && method != "1")
		throw std::invalid_argument(
		    "[" + kf + "] method = " + method +
		    ": only kfEKFNaive and kfEKFAlaDavison are supported (MRPT's kfIKF is not "
		    "implemented and kfIKFFull does not re-linearise)");
	KF_options.loadFromConfigFile(ini, kf);
	reset();
}

void CDynamicKFSLAM2D::syncPkk() const
{
	if (!m_pkkStale) return;
	auto& P = const_cast<KFMatrix&>(m_pkk);
	const Eigen::Index n = m_cov.rows();
	P.setSize(size_t(n), size_t(n));
	P.asEigen() = m_cov.view();
	m_pkkStale = false;
}

void CDynamicKFSLAM2D::setCov(const Eigen::Ref<const ekf::RowMatrixXd>& P)
{
	m_cov.resize(P.rows());
	cov() = P;
}

// ------------------------------------------------------------------------------------------
// The whole state (src/state_store.h)
// ------------------------------------------------------------------------------------------
CDynamicKFSLAM2D::TStateRef CDynamicKFSLAM2D::wholeState() const
{
	return m_store->whole(ekf::TFilterView{*this});
}

const estimator::CPaddedLayout& CDynamicKFSLAM2D::getLayout() const
{
	return m_lifecycle->holdsPassive() ? m_store->expanded({*this}).layout : m_layout;
}

const std::vector<TSlot>& CDynamicKFSLAM2D::getSlots() const
{
	return m_lifecycle->holdsPassive() ? m_store->expanded({*this}).slots : m_slots;
}

const CDynamicKFSLAM2D::KFVector& CDynamicKFSLAM2D::fullMean() const
{
	return m_lifecycle->holdsPassive() ? m_store->expanded({*this}).x : m_xkk;
}

const CDynamicKFSLAM2D::KFMatrix& CDynamicKFSLAM2D::fullCov() const
{
	if (m_lifecycle->holdsPassive()) return m_store->expanded({*this}).P;
	syncPkk();
	return m_pkk;
}

void CDynamicKFSLAM2D::globalUpdate()
{
	ekf::TFilterAccess a{*this};
	m_store->globalUpdate(a);
}

// ------------------------------------------------------------------------------------------
// The step
// ------------------------------------------------------------------------------------------
void CDynamicKFSLAM2D::processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
                                                const mrpt::obs::CSensoryFrame::Ptr& SF)
{
	static const std::string who = "CDynamicKFSLAM2D";
	if (m_failed)
		throw std::runtime_error(
		    who + ": an earlier step failed numerically; call reset() before going on");
	// Parse and validate: throws before anything is changed.
	estimator::TStepInput in = parseStepInput(action, SF, options.parseOptions(), who);
	m_router->validate(in.readings, who);
	m_in = std::move(in);
	++m_step;
	m_report = TStepReport();
	m_report.step = m_step;
	++m_stateVersion;                  // the state store's expanded copy is of the last step
	ekf::TFilterAccess access{*this};  // the modules' hooks
	ekf::CModuleList& modules = *m_modules;
	try
	{
		if (m_store->active()) m_store->startOfStep(access);  // compressed EKF only
		m_router->setContext(ekf::routerContext(access.view()));
		m_routed = m_router->route(m_step, m_in.readings,
		                           [this](int32_t id) { return m_staticBlock.count(id) != 0; });
		modules.afterRoute(access);  // fusion: fused IDs read as their landmark
		m_report.skipped_unknown_object_feature = m_routed.skipped_unknown_object_feature;
		m_report.skipped_dropped_object = m_routed.skipped_dropped_object;
		m_report.classify_candidates = m_routed.candidates;
		m_report.classify_held = m_routed.held;
		m_report.classify_stopped = m_routed.stopped;
		m_report.skipped_unknown_id = m_routed.skipped_unknown_id;
		m_report.skipped_box_corners = m_routed.skipped_box_corners;
		m_report.unknown_id_associated = m_routed.unknown_id_static;
		m_report.unknown_id_new = m_routed.unknown_id_new;
		m_report.classify_restarted = m_routed.restarted;
		m_report.classify_split = m_routed.split;
		m_report.classify_joined = m_routed.joined;
		convertStaticLandmarks(m_routed.converted);  // classify: a parked car drove off
		propagateEgo();                              // Alg. 7
		modules.afterPropagate(access);     // first estimates: x_{k|k-1}; objects predicted
		staticUpdate();                     // Alg. 5
		modules.afterStaticUpdate(access);  // object motion: objects' readings as updates
		for (const auto& m : m_routed.statics()) m_drop.noteSeen(m.reading.id, m_step);
		for (const auto& m : m_routed.objects()) m_drop.noteObjectSeen(m.object, m_step);

		// New entries, the object motion model and drops, committed together (one covariance
		// rewrite; two with a motion model, which needs the new poses in the state first).
		TPending& plan = m_plan;  // its vectors keep their capacity (commit() clears them)
		plan.a = plan.b = ekf::Augmentation();
		plan.blocks.clear();
		plan.remove.clear();
		planFeatures(plan);     // Alg. 3
		planObjectPoses(plan);  // Alg. 4
		if (m_motion->actsOnNewPoses())
		{
			commit(plan);
			applyObjectMotion();                // Alg. 6
			modules.afterMotion(access, plan);  // object motion: velocities of new objects
		}
		planDrops(plan);
		modules.planDrops(access, plan);  // object drop; object motion: fallbacks (lost objects)
		commit(plan);
		modules.afterCommit(access);  // fusion, linked merge, live merge
		modules.endOfStep(access);    // first estimates: record the new landmarks'
		if (m_store->active()) m_store->endOfStep(access);  // compressed EKF only
	}
	catch (const std::exception& e)
	{
		// A numerical failure inside a step (e.g. an innovation covariance that is not positive
		// definite with extreme noise settings) leaves the state half-updated: never go on
		// silently from there.
		m_failed = true;
		throw std::runtime_error(who + ": step " + std::to_string(m_step) +
		                         " failed, the filter must be reset(): " + std::string(e.what()));
	}
}

bool CDynamicKFSLAM2D::mapEmpty() const
{
	return m_layout.size() == (m_modules->odometryBias() ? 1u : 0u);
}

void CDynamicKFSLAM2D::propagateEgo()
{
	const bool skip = options.skip_prediction_on_empty_map && mapEmpty();
	ekf::COdometryBiasModule* bias = m_modules->odometryBias();  // odometry_bias != none
	// The step's duration, recorded on every step (also when the prediction is skipped).
	const double dt = bias ? bias->stepDuration(m_in.stamp, m_step) : 0;
	m_lastF.reset();
	if (skip) return;
	const Eigen::Matrix3d& S = options.motion_noise_from_action ? m_in.U : options.Sigma_w;
	auto x = m_xkk.asEigen();
	auto P = cov();
	Eigen::Matrix3d F;
	const ekf::CFirstEstimateModule* fej = m_modules->firstEstimates();
	const Eigen::Vector3d* fejPrev = fej ? fej->predictedEgo() : nullptr;
	if (bias)  // the bias block is block 0
		bias->propagate(x, P, m_in.u, S, m_layout.first(0), dt, fejPrev, F);
	else
		ekf::propagate(x, P, m_in.u, S, fejPrev, &F);
	m_lastF = F;
	OnNormalizeStateVector();
}

estimator::TUpdateContext CDynamicKFSLAM2D::updateContext() const
{
	estimator::TUpdateContext ctx;
	ctx.model = options.measurement_model;
	ctx.R = options.Sigma_v;
	ctx.sensor_pose = m_in.sensor_pose;
	ctx.gate_threshold = m_engineGated ? estimator::gateThreshold2Dof(options.innovation_gate)
	                                   : std::numeric_limits<double>::infinity();
	if (const ekf::CFirstEstimateModule* fej = m_modules->firstEstimates())
		ctx.jacobians = [this, fej](int32_t id, const Eigen::Vector3d& ego, models::Matrix23d& Jx,
		                            Eigen::Matrix2d& Jf)
		{ fej->jacobians(options.measurement_model, m_in.sensor_pose, id, ego, Jx, Jf); };
	return ctx;
}

void CDynamicKFSLAM2D::staticUpdate()
{
	std::vector<estimator::TStaticObservation> obs;
	for (const auto& m : m_routed.with(estimator::Route::StaticKnown))
		obs.push_back({m.reading.id, m.reading.z, m_layout.first(m_staticBlock.at(m.reading.id))});
	auto x = m_xkk.asEigen();
	auto P = cov();
	const estimator::TUpdateResult r =
	    estimator::state::update(*m_engine, x, P, obs, updateContext());
	m_report.static_updates = r.updates;
	m_report.gated_out = r.gated_out;
	m_report.nis_static = r.nis;
	m_report.nis_static_dof = r.nis_dof;
	OnNormalizeStateVector();
}

std::vector<TTrackedBox> CDynamicKFSLAM2D::trackedBoxes() const
{
	return ekf::trackedBoxes({*this});  // src/router_context.h
}

// ------------------------------------------------------------------------------------------
// The capability modules (src/modules/)
// ------------------------------------------------------------------------------------------
void CDynamicKFSLAM2D::convertStaticLandmarks(
    const std::vector<estimator::TRoutedStep::TConversion>& c)
{
	ekf::TFilterAccess a{*this};
	ekf::convertStaticLandmarks(a, c);
}

bool CDynamicKFSLAM2D::mergeObjects(int32_t from, int32_t into)
{
	ekf::TFilterAccess a{*this};
	return ekf::mergeObjects(a, from, into);
}

void CDynamicKFSLAM2D::forgetStatic(int32_t id)
{
	m_drop.forget(id);
	m_modules->staticForgotten(id);
}

std::vector<std::string> CDynamicKFSLAM2D::enabledModules() const { return m_modules->names(); }

const std::map<int32_t, Eigen::VectorXd>& CDynamicKFSLAM2D::getObjectModeProbabilities() const
{
	static const std::map<int32_t, Eigen::VectorXd> none;
	const ekf::CObjectMotionModule* motion = m_modules->objectMotion();
	return motion ? motion->modeProbabilities() : none;
}

std::vector<std::string> CDynamicKFSLAM2D::objectModeNames() const
{
	return estimator::modeNames(*m_motion);
}

size_t CDynamicKFSLAM2D::moduleHookCalls() const { return m_modules->hookCalls(); }

const std::vector<estimator::TFusionPair>& CDynamicKFSLAM2D::getFusedLandmarks() const
{
	static const std::vector<estimator::TFusionPair> none;
	const ekf::CLandmarkFusionModule* fusion = m_modules->fusion();
	return fusion ? fusion->fusions() : none;
}

std::optional<Eigen::Vector2d> CDynamicKFSLAM2D::firstEstimate(int32_t id) const
{
	const ekf::CFirstEstimateModule* fej = m_modules->firstEstimates();
	return fej ? fej->firstEstimate(id) : std::nullopt;
}

std::optional<Eigen::Vector3d> CDynamicKFSLAM2D::lastPredictedEgo() const
{
	const ekf::CFirstEstimateModule* fej = m_modules->firstEstimates();
	const Eigen::Vector3d* e = fej ? fej->predictedEgo() : nullptr;
	return e ? std::optional<Eigen::Vector3d>(*e) : std::nullopt;
}

}  // namespace dynslam
