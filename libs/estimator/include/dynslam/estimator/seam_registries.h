#pragma once
/** @file seam_registries.h
 * The registries of the estimator's four seams (registry.h; doc/architecture.md): name ->
 * factory, capabilities. The EKF (CDynamicKFSLAM2D::reset()), the framework's back-ends and the
 * apps make their implementations here. Engines that need MRPT (jcbb) are added by libs/ekf
 * (dynslam/ekf/ekf_registries.h: ekfUpdateEngines()); this library stays pure Eigen. */
#include <dynslam/estimator/constant_velocity.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/estimator/registry.h>
#include <dynslam/estimator/robust_update_engines.h>
#include <dynslam/estimator/state_lifecycle.h>
#include <dynslam/estimator/update_engine.h>

namespace dynslam::estimator
{
struct TClassifyParams;
struct TBoxTrackerParams;

// --- route (feature_labels) ------------------------------------------------------------------
struct TRouterParams
{
	const TClassifyParams* classify = nullptr;  ///< classify: its parameters (defaults if null)
	const TBoxTrackerParams* boxes = nullptr;   ///< boxes: the tracker's (defaults if null)
};
struct TRouterCaps
{
	bool classifies = false;  ///< decides static / moving itself (IDs need not tell)
};
using CRouterRegistry = CRegistry<IMeasurementRouter, TRouterParams, TRouterCaps>;
/** ids (CIdRangeRouter), classify (CClassifyingRouter), boxes (CBoxRouter: the tracker and
 * classify). */
const CRouterRegistry& routers();

// --- object motion model (object_model) ------------------------------------------------------
struct TObjectMotionParams
{
	bool smoothing = false;  ///< paper: the smoothing (Alg. 6) on
	Eigen::Matrix3d Sigma_s = Eigen::Matrix3d::Identity() * 1e-2;
	TCvParams cv;  ///< cv, ctrv, ca (cv.gate: the chi-square threshold, not a probability)
};
struct TObjectMotionCaps
{
	/** The model gives each object a velocity block (IObjectMotionModel::velocityDim() > 0):
	 * objects are predicted and their sightings are updates (doc/state-layout.md). */
	bool object_centric = false;
	/** The paper's smoothing (Alg. 6, Sigma_s; needs the last 3 poses of an object). */
	bool smoothing = false;
	bool framework = true;  ///< implemented by the framework's Alg. 1 back-end
	bool window = true;     ///< implemented by the framework's windowed back-ends
	/** The key of its process noise's spectral density (object-centric models; every entry
	 * must be > 0 in the framework, whose motion term needs an invertible Q). */
	const char* noise_key = "cv_accel_psd";
};
using CObjectMotionRegistry = CRegistry<IObjectMotionModel, TObjectMotionParams, TObjectMotionCaps>;
/** paper (CNoObjectMotion, or CPaperSmoothing if smoothing), paper_smoothing (CPaperSmoothing),
 * cv (CConstantVelocity), ctrv (CConstantTurnRate), ca (CConstantAcceleration), mm
 * (CMultipleModel). */
const CObjectMotionRegistry& objectMotionModels();

// --- update (outlier_method) -----------------------------------------------------------------
struct TUpdateEngineParams
{
	double gate_probability = 0;  ///< innovation_gate (jcbb: its confidence)
	double robust_c = 2.0;
	int robust_iterations = 5;
	TGateRecoveryParams recovery;
};
struct TUpdateEngineCaps
{
	/** The step's gate threshold (innovation_gate) is handed to the engine; false: none. */
	bool gate = true;
	/** It needs a gate (innovation_gate > 0). */
	bool needs_gate = false;
};
using CUpdateEngineRegistry = CRegistry<IUpdateEngine, TUpdateEngineParams, TUpdateEngineCaps>;
/** gate, none (CSparseUpdateEngine with / without the gate), huber, cauchy (CRobustUpdateEngine),
 * gate_recovery (CGateRecoveryUpdateEngine). libs/ekf adds jcbb. */
const CUpdateEngineRegistry& updateEngines();

// --- the state's lifecycle (static_update = compressed or not) ---------------------------
struct TLifecycleParams
{
	int passive_after = 3;
	int batch = 8;
};
struct TLifecycleCaps
{
	bool rewrites_storage = false;  ///< see IStateLifecycle::rewritesStorage()
};
using CLifecycleRegistry = CRegistry<IStateLifecycle, TLifecycleParams, TLifecycleCaps>;
/** full (CFullStateLifecycle), compressed (CCompressedLifecycle). */
const CLifecycleRegistry& stateLifecycles();
}  // namespace dynslam::estimator
