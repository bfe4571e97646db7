#pragma once
/** @file ISlamBackend.h
 * What every SLAM back-end of the project offers to the apps: the dynamic EKF
 * (CDynamicKFSLAM2D), the optimization framework's configurations (Alg. 1, VDO-SLAM-like,
 * DynaSLAM II-like, CubeSLAM-like, ClusterSLAM-like) and the static baseline wrapper.
 * All are driven by MRPT's (action, sensory frame) pairs, one per step. */
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dynslam
{
struct TStaticLandmarkEstimate
{
	int32_t id;
	Eigen::Vector2d mean;
	Eigen::Matrix2d cov;
	bool in_state = true;  ///< false: dropped (out of range), last estimate recorded
};

struct TObjectFeatureEstimate
{
	int32_t object, feature, id;
	bool at_time0;  ///< true: f_0 (first sighting); false: f_t
	int step;       ///< step of the estimate (first sighting step for f_0)
	Eigen::Vector2d mean;
	Eigen::Matrix2d cov;
};

struct TObjectPoseEstimate
{
	int step;
	Eigen::VectorXd mean;  ///< (dx, dy, dtheta), or (dx, dy) for one-feature objects
	Eigen::MatrixXd cov;   ///< marginal covariance
	/** Velocity at that step, for object models with a velocity state (object_model = cv |
	 * ctrv: world-frame velocity of the reference point, and turn rate for 3-dof poses;
	 * models/object_motion.h) and its marginal covariance; empty otherwise. */
	Eigen::VectorXd velocity;
	Eigen::MatrixXd velocity_cov;
	/** Multiple-model objects (object_model = mm): the mode probabilities after that step's
	 * readings, in the order of ISlamBackend::objectModeNames(); empty otherwise. */
	Eigen::VectorXd mode_probabilities;
	bool in_state;  ///< false: dropped, recorded with its marginal covariance at drop time
};

/** Everything known of one moving object. */
struct TObjectTrack
{
	int32_t object;
	int first_step;    ///< the object's time 0
	int num_features;  ///< features seen at the first sighting (the object's feature set)
	/** Readings of features first seen after the object's first sighting that are not in its
	 * feature set (no f_0: skipped, never used; with feature_labels = ids every such feature;
	 * with classify, late joining gives them an f_0 instead), and how many distinct features
	 * they came from. Also summed over objects per step in
	 * TStepReport::skipped_unknown_object_feature. */
	size_t skipped_late_readings = 0;
	int skipped_late_features = 0;
	std::vector<TObjectPoseEstimate> poses;  ///< ascending step: dropped ones, then in-state ones
};

/** Counts of what one step did, and what it skipped and why. */
struct TStepReport
{
	int step = -1;
	size_t static_updates = 0, static_new = 0;
	size_t object_features_new = 0, object_features_t = 0, object_poses_added = 0;
	size_t smoothing_updates = 0;
	size_t skipped_unknown_object_feature =
	    0;                               ///< feature of a known object not seen at its time 0
	size_t skipped_pose_degenerate = 0;  ///< gamma undetermined (one feature seen, coinciding)
	size_t dropped_static = 0, dropped_poses = 0, dropped_time_t = 0;
	/** Static landmarks pruned (prune_min_sightings / prune_window: read too rarely in their
	 * first steps; recorded per record_dropped like dropped_static, counted apart). */
	size_t pruned_static = 0;
	/** drop_object_after_unseen_steps: objects dropped from the state at this step (their
	 * tracks recorded per record_dropped), and readings of dropped objects (skipped). */
	size_t dropped_objects = 0, skipped_dropped_object = 0;
	/** fuse_landmarks_prob: static landmarks fused into another one (re-identified; recorded per
	 * record_dropped like dropped_static), and readings skipped because another reading of
	 * the step already went to the same fused landmark. */
	size_t fused_static = 0, skipped_fused_duplicate = 0;
	size_t gated_out = 0;  ///< static measurements rejected by the innovation gate
	/** object_model = cv: object readings used as updates, rejected by cv_gate. */
	size_t object_feature_updates = 0, object_gated_out = 0;
	/** cv_fallback_steps > 0: objects lost at this step (velocity and pose removed, back to the
	 * paper's formulation) and objects given a new velocity from two poses after a fallback. */
	size_t object_fallbacks = 0, object_reinits = 0;
	double nis_static = 0;  ///< NIS of the static update (0 if none)
	size_t nis_static_dof = 0;
	/** feature_labels = classify (doc/results/classification.md): readings of undecided tracks and
	 * of static tracks held back as inconsistent (both unused), readings with ID -1 (skipped),
	 * static landmarks reclassified moving and dropped from the state. */
	size_t classify_candidates = 0, classify_held = 0, skipped_unknown_id = 0;
	/** Readings with ID -1 (MRPT's unknown landmark) associated with a static landmark of the
	 * state, and those that started a new static landmark (CRangeBearingKFSLAM2D's rule; the
	 * ones that could not be associated at all are in skipped_unknown_id). */
	size_t unknown_id_associated = 0, unknown_id_new = 0;
	/** feature_labels = boxes: corner readings of boxes whose track is not confirmed (or that
	 * the tracker ignored), not used. */
	size_t skipped_box_corners = 0;
	size_t reclassified_static = 0;
	/** Static landmarks reclassified moving and turned into object f_0 by state surgery
	 * (classify_reclassify = surgery; reclassified_static counts the dropped ones, restart). */
	size_t converted_static = 0;
	size_t classify_stopped = 0;    ///< moving tracks decided static (their object stopped)
	size_t dropped_candidates = 0;  ///< candidate landmarks removed (decided moving, forgotten)
	/** Tracks restarted under a fresh ID after a break (reading inconsistent with the track's
	 * assignment: its ID reused), split off their object, joined an earlier object (router);
	 * late joiners given their f_0 (EKF, the object's pose computable). */
	size_t classify_restarted = 0, classify_split = 0, classify_joined = 0;
	size_t object_features_joined = 0;
	/** classify_merge_linked: linked objects merged into the lost object (its motion model
	 * predicted it across the gap), and links not merged (the lost object has no velocity). */
	size_t objects_merged = 0, merges_skipped = 0;
	/** classify_merge_live: live objects merged into another one they move rigidly with. */
	size_t objects_merged_live = 0;
};

/** A tracked box of the last step (issue 31; the multi-object tracking metrics): one track's
 * footprint in the robot frame of that step, as the back-end estimates it (its own ego
 * estimate places it; the truth is compared in the true robot frame, as KITTI scores in the
 * camera frame). */
struct TTrackedBox
{
	int32_t track = -1;  ///< the back-end's track ID (persistent over the run)
	std::string cls;     ///< class, e.g. "Car"
	double score = 0;    ///< confidence (sAMOTA's thresholds): the score of its last box
	Eigen::Vector3d pose = Eigen::Vector3d::Zero();    ///< centre x, y [m], heading [rad]
	Eigen::Vector2d extent = Eigen::Vector2d::Zero();  ///< length, width [m]
};

/** Common interface of the back-ends. */
class ISlamBackend
{
public:
	virtual ~ISlamBackend() = default;
	/** Short name used in tables and file names, e.g. "dynamic_ekf". */
	virtual std::string name() const = 0;
	/** One step: odometry action into this step, then the observations of this step. */
	virtual void processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
	                                      const mrpt::obs::CSensoryFrame::Ptr& SF) = 0;
	virtual mrpt::poses::CPosePDFGaussian getEgoPose() const = 0;
	/** The live map: the static landmarks in the state (in_state = true). */
	virtual std::vector<TStaticLandmarkEstimate> getStaticLandmarks() const = 0;
	/** The static landmarks dropped from the state (out of range too long), each with its last
	 * estimate (in_state = false); empty for back-ends that never drop. */
	virtual std::vector<TStaticLandmarkEstimate> getDroppedStaticLandmarks() const = 0;
	virtual std::vector<TObjectFeatureEstimate> getObjectFeatures() const = 0;
	virtual std::map<int32_t, TObjectTrack> getObjectTracks() const = 0;
	virtual const TStepReport& getLastStepReport() const = 0;
	/** The names of the objects' motion modes (TObjectPoseEstimate::mode_probabilities); empty
	 * for single-model back-ends. */
	virtual std::vector<std::string> objectModeNames() const { return {}; }
	/** The confirmed box tracks the back-end reports for the last step (issue 31: the
	 * `tracker_baseline` row, and the filters with feature_labels = boxes); empty for back-ends
	 * that track no boxes. */
	virtual std::vector<TTrackedBox> trackedBoxes() const { return {}; }
};

/** Every static landmark estimated so far: the live map, then the dropped ones (what the apps
 * write to landmarks.csv and evaluate). */
inline std::vector<TStaticLandmarkEstimate> allStaticLandmarks(const ISlamBackend& b)
{
	std::vector<TStaticLandmarkEstimate> out = b.getStaticLandmarks();
	const std::vector<TStaticLandmarkEstimate> dropped = b.getDroppedStaticLandmarks();
	out.insert(out.end(), dropped.begin(), dropped.end());
	return out;
}
}  // namespace dynslam
