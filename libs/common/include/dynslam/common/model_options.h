#pragma once
/** @file model_options.h
 * The model of the dynamic SLAM problem (paper Section II): measurement model and noise,
 * motion noise, prior, object-pose map residual, smoothing, drop policies. Section
 * [DynamicKFSLAM] of the INI files, and the capability modules' sections [ObjectModel],
 * [OdometryBias], [Classify] (dynslam/common/model_keys.h). Shared by every back-end: the dynamic
 * EKF (CDynamicKFSLAM2D::TOptions is this struct) and the framework's configurations
 * (framework::TBackendOptions::model), so it lives below both, in dynslam::common. */
#include <dynslam/common/box_tracker_options.h>
#include <dynslam/common/odometry_bias_options.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/estimator/classifying_router.h>
#include <dynslam/estimator/constant_velocity.h>
#include <dynslam/estimator/drop_policy.h>
#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <iosfwd>
#include <string>

namespace dynslam
{
/** Options, section [DynamicKFSLAM] (the EKF's KF_options in [DynamicKFSLAM_KalmanFilter]). */
struct TModelOptions : public mrpt::config::CLoadableOptions
{
	/** Reads the core keys from [section] and the modules' keys from their fixed sections
	 * ([ObjectModel], [OdometryBias], [Classify]; the switches object_model, odometry_bias and
	 * feature_labels stay in [section]). Unknown keys of any of them are errors, and so is a
	 * module key in [section]: "[DynamicKFSLAM] key classify_alpha moved to section [Classify]". */
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
	                        const std::string& section) override;
	/** The core keys, then each module's section ([OdometryBias] when enabled, [Classify] when
	 * feature_labels != ids): the dump reads back as an INI. */
	void dumpToTextStream(std::ostream& out) const override;
	/** Throws std::invalid_argument naming the offending option. */
	void validate() const;
	/** What the step-input parser and the drop policy of every back-end take from these. */
	TParseOptions parseOptions() const;
	estimator::TDropOptions dropOptions() const;

	/** measurement_model (required): cartesian (paper, Sigma_v on the sensor-frame
	 * point) or range_bearing (MRPT's; Sigma_v = diag(std_range^2, std_bearing^2)). */
	models::MeasurementModel measurement_model = models::MeasurementModel::Cartesian;
	/** Sigma_v (required): measurement noise covariance in the model's space [m^2] or
	 * [m^2, rad^2]. */
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Identity() * 1e-4;
	/** motion_noise = action (the CActionRobotMovement2D covariance, rotated by the
	 * heading, as CRangeBearingKFSLAM2D does) or config (Sigma_w on the increment). */
	bool motion_noise_from_action = true;
	Eigen::Matrix3d Sigma_w = Eigen::Matrix3d::Identity() * 1e-4;  ///< [m^2, m^2, rad^2]
	Eigen::Vector3d initial_pose = Eigen::Vector3d::Zero();        ///< x_0 mean
	Eigen::Matrix3d Sigma_0 = Eigen::Matrix3d::Zero();             ///< x_0 covariance (PSD)
	/** prior_gauge (issue 13, doc/state-layout.md "The prior gauge"): prior (default: the EKF
	 * starts with the ego covariance Sigma_0) or anchor (the EKF runs with the initial pose as
	 * the gauge, zero ego covariance, and Sigma_0 enters only its reported covariances as the
	 * uncertain rigid transform of the whole estimate, P + N Sigma_0 N^T, models/gauge.h).
	 * EKF only: the framework back-ends reject anchor. */
	bool prior_gauge_anchor = false;
	/** Sigma_xi: per-feature residual covariance of the object pose map (paper 0.1 I). */
	Eigen::Matrix2d Sigma_xi = Eigen::Matrix2d::Identity() * 0.1;
	bool smoothing = false;  ///< Alg. 6 on/off (paper: off on the highway)
	Eigen::Matrix3d Sigma_s = Eigen::Matrix3d::Identity() * 1e-2;  ///< smoothing covariance
	/** object_model (issue 13; doc/state-layout.md "Object-centric motion models"): paper
	 * (default: objects follow their features, Alg. 3-4, smoothing per `smoothing`),
	 * paper_smoothing (= paper with smoothing = true), cv (constant velocity: each object's pose
	 * and world-frame velocity are predicted every step and its sightings update ego, pose and
	 * body-frame features together), ctrv (the same with a constant turn rate: the velocity
	 * turns at omega, models::ctrvPredict; it reads the cv_* keys), ca (constant acceleration:
	 * the velocity block is [v; a], driven by white jerk; the cv_* keys and ca_jerk_psd,
	 * ca_accel_prior_std, estimator/constant_acceleration.h), mm (multiple models: stationary,
	 * cv, turn and manoeuvre modes mixed per object by their probabilities; the cv_* keys and
	 * mm_switch_prob, mm_manoeuvre_psd, estimator/multiple_model.h; EKF only). */
	std::string object_model = "paper";
	/** An object-centric model (objects have a velocity and update the state: cv, ctrv): the
	 * capability of object_model in estimator::objectMotionModels(); false if unknown. */
	bool objectCentric() const;
	/** Section [ObjectModel]. cv: cv_dt [s per step] (required with cv), cv_accel_psd
	 * (white-acceleration spectral densities ax, ay, alpha), cv_velocity_prior_std (vx, vy, omega;
	 * > 0), cv_gate (chi-square probability of the per-reading gate on object readings, 0 = no
	 * gate; a gated reading is not used and counted in TStepReport::object_gated_out, the object
	 * coasts on its prediction), cv_fallback_steps (an object whose readings were all gated out at
	 * that many consecutive steps falls back to the paper's formulation until two poses give it a
	 * new velocity; 0 = off, the default), cv_heading_inflation (object readings' noise Sigma_v + c
	 * P_thth h h^T, h the reading's Jacobian on the ego heading; 0 = off, the default;
	 * estimator::TCvParams::heading_inflation). */
	estimator::TCvParams cv;
	double cv_gate = 0;
	bool drop_time_t_features = true;  ///< drop f_t after pose augmentation
	int keep_last_poses = 1;           ///< K >= 1 object poses kept per object (3 with smoothing)
	/** Drop static landmarks unseen for this many steps (0 = never). Off by default:
	 * loop closure needs them. */
	int drop_static_after_unseen_steps = 0;
	/** Pruning of clutter (issue 29; estimator::TDropOptions): a static landmark read in fewer
	 * than prune_min_sightings (k >= 2) of the prune_window (W >= k) steps from its first
	 * reading on is dropped at the end of that window, recorded per record_dropped; both 0
	 * (default) = off. The EKF and Alg. 1 (the windowed back-ends reject it). */
	int prune_min_sightings = 0;
	int prune_window = 0;
	/** An object with no used reading for this many steps is dropped: its blocks leave the
	 * state, its poses (and velocity) and time-0 features are recorded per record_dropped, its
	 * later readings are skipped and counted (TStepReport::skipped_dropped_object); 0 = never
	 * (default). The dynamic EKF with feature_labels = ids only. */
	int drop_object_after_unseen_steps = 0;
	/** Landmark fusion (issue 29; estimator/landmark_fusion.h, doc/robustness.md): two static
	 * landmarks are one point (a landmark re-identified under a new ID after a track break)
	 * when their difference passes a chi-square test with this probability (2 dof); the newer
	 * one is fused into the older one and its ID read as the older one's. 0 = off (default),
	 * else in (0, 1). The dynamic EKF with feature_labels = ids and a full state only. */
	double fuse_landmarks_prob = 0;
	/** Reproduce CRangeBearingKFSLAM2D, which skips the prediction (mean and covariance)
	 * while the map is empty. Off by default: it ignores the motion before the first
	 * landmark. Only for comparisons with MRPT's filter. */
	bool skip_prediction_on_empty_map = false;
	/** static_update = sparse (default): the update engine estimator::CSparseUpdateEngine,
	 * the EKF update as a rank-2k correction using only the non-zero columns of H
	 * (ekf::sparseUpdate, O(n^2 k)); equal to MRPT's kfEKFNaive within rounding (tested), and
	 * numerically stable where MRPT's dense P <- (I - K H) P is not (it lost positive
	 * definiteness in 3 of 25 highway runs at noise level w3v1, doc/results/results.md).
	 * static_update = mrpt: CMrptUpdateEngine, MRPT's own update (KF_options.method) run by
	 * runOneKalmanIteration with its prediction skipped (doc/architecture.md). */
	bool sparse_static_update = true;
	/** static_update = compressed (sets sparse_static_update too): the sparse update on the
	 * exact compressed EKF (estimator::CCompressedLifecycle, compressed_state.h): static
	 * landmarks left behind are kept out of the working state and brought up to date when
	 * needed; equal to the full EKF to rounding. */
	bool compressed_static_update = false;
	/** static_update = compressed: a static landmark unseen for this many steps becomes
	 * passive (leaves the working state), >= 1 (INI key compressed_passive_after). */
	int compressed_passive_after = 3;
	/** static_update = compressed: landmarks are made passive only when at least this many
	 * are due, >= 1 (INI key compressed_batch; each compression adds |active| entries). */
	int compressed_batch = 8;
	/** Innovation gate for static-landmark updates: a measurement whose squared
	 * Mahalanobis distance (with its own 2x2 innovation covariance) exceeds the chi-square
	 * quantile of this probability (2 dof) is not used, and counted
	 * (TStepReport::gated_out). 0 = no gate (default; MRPT's filter has none). */
	double innovation_gate = 0;
	/** outlier_method (issue 17; estimator/robust_update_engines.h): gate (default: the
	 * sparse update with the innovation_gate above, today's behaviour, kept as the default
	 * because the other methods were not yet checked on held-out real data), none (no gate even
	 * if innovation_gate > 0), huber / cauchy (IRLS with robust_kernel_c [Mahalanobis units
	 * of Sigma_v] and at most robust_iterations updates; no gate), gate_recovery (the gate
	 * with innovation_gate > 0 plus ego-covariance inflation by recovery_inflation after
	 * recovery_count consecutive rejections of a landmark with >= recovery_min_updates
	 * accepted readings), jcbb (joint compatibility of the step's readings at the confidence
	 * innovation_gate > 0: MRPT's JCBB plus the joint chi-square test, CJcbbUpdateEngine in
	 * libs/ekf). Methods other than gate need static_update = sparse. Used by the EKF only:
	 * the framework back-ends (libs/framework) neither gate nor use outlier_method. */
	std::string outlier_method = "gate";
	double robust_kernel_c = 2.0;
	int robust_iterations = 5;
	int recovery_count = 5;
	double recovery_inflation = 4.0;
	int recovery_min_updates = 3;
	/** record_dropped: keep the last estimate of every dropped object pose and static
	 * landmark (getObjectTracks, getDroppedStaticLandmarks); default true. false: dropped
	 * entries are forgotten, so memory stays bounded in endless runs. */
	bool record_dropped = true;
	/** First-estimate Jacobians (Huang, Mourikis, Roumeliotis, ICRA/ISER 2008), default
	 * off. On: the ego propagation Jacobian uses the ego position difference
	 * p_{k+1|k} - p_{k|k-1} of the predicted (first) estimates instead of R(theta_{k|k}) u,
	 * and the static-landmark measurement Jacobians (update and innovation gate, both
	 * update paths) are evaluated at the predicted ego pose and the landmark's first
	 * estimate (its mean at the end of the step in which it was initialized); the
	 * innovation still uses the current estimates. Object steps are unchanged. The
	 * linearized system then keeps the 3-dof unobservable subspace (global translation
	 * and rotation) of the true one. See doc/results/results.md. */
	bool first_estimate_jacobians = false;
	/** Online odometry bias estimation (issue 17): odometry_bias = none | rate | rate_scale
	 * and its keys (section [OdometryBias]), dynslam/common/odometry_bias_options.h. Only the
	 * dynamic EKF supports it. */
	TOdometryBiasOptions odometry_bias;
	/** feature_labels (issue 12, doc/results/classification.md): ids (default: the ID ranges of
	 * dynslam/core/landmark_ids.h say what each reading is) or classify (every ID >= 0 is an
	 * anonymous track, classified online by estimator::CClassifyingRouter with the
	 * classify_* keys of section [Classify]; EKF only) or boxes (detector boxes without IDs:
	 * estimator::CBoxRouter, the tracker of [BoxTracker] then classify; EKF only). */
	std::string feature_labels = "ids";
	estimator::TClassifyParams classify;
	/** feature_labels = boxes (issue 31, doc/boxes.md): the box tracker and its output rule,
	 * section [BoxTracker] (the same keys as the tracker_baseline row). */
	TBoxTrackerOptions boxes;
};
}  // namespace dynslam
