#pragma once
/** @file CDynamicKFSLAM2D.h
 * Dynamic EKF-SLAM (Chiu, arXiv 2207.05043, Alg. 2-7) as a subclass of MRPT's
 * CKalmanFilterCapable<3,2,2,3>.
 *
 * State layout (design decision, doc/state-layout.md): the ego pose (x, y, theta), then a
 * sequence of 2-dof slots described by a slot table:
 *   static landmark | object feature at time 0 | object feature at time t |
 *   object pose part A [dx, dy] | object pose part B [dtheta, pad].
 * The pad is an independent unit-variance dummy with zero cross-covariance; no model touches
 * it and no output shows it. A one-feature object has a translation-only pose (part A only).
 *
 * One step (processActionObservation), built on the estimator core (libs/estimator,
 * doc/architecture.md): parse -> route -> propagate -> update -> augment -> motion model ->
 * drop -> commit.
 *  1. Parse (dynslam/common/step_input.h) and route the readings (IMeasurementRouter: static
 *     known / new, object first sighting / time t, skip).
 *  2. Prediction with the odometry (Alg. 7, ekf::propagate) and update with the tracked static
 *     landmarks (Alg. 5) by the update engine (IUpdateEngine: the sparse update, or MRPT's
 *     runOneKalmanIteration with its prediction skipped).
 *  2b. Feature augmentation (Alg. 3): new static landmarks, time-0 features of new objects,
 *     time-t features of known objects.
 *  3. Object-pose augmentation (Alg. 4) with Sigma_xi, for every object seen this step.
 *  4. Object motion model (IObjectMotionModel): none, or the smoothing update (Alg. 6) for
 *     objects with poses at t-2, t-1, t.
 *  5. Drops: time-t features (optional, default on), object poses older than the last K,
 *     static landmarks out of range for too long (optional, default off). Dropped poses and
 *     landmarks are recorded with their last mean and marginal covariance.
 * Steps 2, 3 and 5 are planned on the state extended by the pending entries and written to
 * the covariance in one rewrite per step (two with smoothing), equal to doing them one by one.
 * Every measurement is used once: a new feature's measurement initializes it, only features
 * tracked before this step update the state.
 *
 * Input: a CActionCollection with a CActionRobotMovement2D, and a CSensoryFrame whose first
 * CObservationBearingRange holds static landmarks and object features, told apart by ID
 * (dynslam/core/landmark_ids.h). Bad input throws std::runtime_error (nothing is changed) or is
 * skipped and counted, as documented per case in getLastStepReport(). */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/common/model_options.h>
#include <dynslam/common/step_input.h>
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/square_buffer.h>
#include <dynslam/ekf/object_world_estimate.h>
#include <dynslam/estimator/compressed_state.h>
#include <dynslam/estimator/drop_policy.h>
#include <dynslam/estimator/landmark_fusion.h>
#include <dynslam/estimator/live_merge.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/object_modes.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/estimator/state_layout.h>
#include <dynslam/estimator/state_lifecycle.h>
#include <dynslam/estimator/update_engine.h>
#include <mrpt/bayes/CKalmanFilterCapable.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace dynslam
{
namespace ekf
{
struct TFilterAccess;  // the capability modules' access (src/modules/filter_module.h)
struct TFilterView;    // the components' read-only access (src/modules/filter_module.h)
class CModuleList;
class CStateStore;         // the state's lifecycle in the filter (src/state_store.h)
class CMrptKalmanAdapter;  // MRPT's hooks' bodies (src/mrpt_kalman_adapter.h)
class CPriorGauge;         // src/gauge/prior_gauge.h
}  // namespace ekf

/** What one 2-dof slot of MRPT's storage (after the ego pose) holds: a view of the typed
 * layout (estimator::CPaddedLayout, getLayout()) for MRPT's landmark indices and for tests. */
enum class SlotKind : uint8_t
{
	StaticLandmark,
	ObjectFeature0,   ///< feature of a moving object at its first sighting (time 0)
	ObjectFeatureT,   ///< feature of a moving object at the current time t
	ObjectPoseA,      ///< [dx, dy] of an object pose xi_t
	ObjectPoseB,      ///< [dtheta, pad] of an object pose xi_t
	ObjectVelocityA,  ///< [vx, vy] of an object velocity block (object-centric models)
	ObjectVelocityB,  ///< a further slot: [omega, pad]; ca: [omega, ax], [ay, alpha]
	OdometryBias,     ///< [b_w, pad] or [b_w, s] (odometry_bias != none; the first slot)
	Compressed        ///< static_update = compressed: accumulated matrices (compressed_state.h)
};
const char* toString(SlotKind k);

/** One entry of the slot table. */
struct TSlot
{
	SlotKind kind;
	int32_t id = -1;       ///< landmark ID (static / object features), -1 for poses
	int32_t object = -1;   ///< object index (object slots)
	int32_t feature = -1;  ///< feature index within the object (object features)
	int step = -1;         ///< time step of xi (poses) or of the measurement (time-t features)
};

class CDynamicKFSLAM2D : public mrpt::bayes::CKalmanFilterCapable<3, 2, 2, 3>, public ISlamBackend
{
public:
	using Base = mrpt::bayes::CKalmanFilterCapable<3, 2, 2, 3>;

	/** Options, section [DynamicKFSLAM] (KF_options in [DynamicKFSLAM_KalmanFilter]): the
	 * model shared with the framework, dynslam/common/model_options.h. */
	using TOptions = TModelOptions;
	TOptions options;
	CDynamicKFSLAM2D();
	~CDynamicKFSLAM2D() override;
	// Not copyable (KF_options holds a reference to the logger's level, see mrpt-notes).
	CDynamicKFSLAM2D(const CDynamicKFSLAM2D&) = delete;
	CDynamicKFSLAM2D& operator=(const CDynamicKFSLAM2D&) = delete;
	/** Clears the map and sets the ego pose to options.initial_pose / Sigma_0. */
	void reset();
	/** Loads `options` from [section] and `KF_options` from [section_KalmanFilter], validates
	 * and resets. Required keys throw when missing. */
	void loadOptions(const mrpt::config::CConfigFileBase& ini,
	                 const std::string& section = "DynamicKFSLAM");
	/** One filter step (see the file comment). Throws std::runtime_error on bad input (wrong
	 * action type, NaN/Inf, duplicate or invalid IDs), leaving the filter unchanged. */
	void processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
	                              const mrpt::obs::CSensoryFrame::Ptr& SF) override;
	std::string name() const override { return "dynamic_ekf"; }
	/** The seams of the step (doc/architecture.md): by default the options' implementations
	 * (made by reset()); one set here is kept by reset() and loadOptions(). Call reset() after
	 * setting one. */
	void setRouter(std::unique_ptr<estimator::IMeasurementRouter> r);
	void setUpdateEngine(std::unique_ptr<estimator::IUpdateEngine> e);
	void setObjectMotionModel(std::unique_ptr<estimator::IObjectMotionModel> m);
	/** The state's lifecycle (how it is stored between steps: full or compressed); reset()
	 * throws std::invalid_argument if it cannot compose with the update engine. */
	void setStateLifecycle(std::unique_ptr<estimator::IStateLifecycle> l);
	const estimator::IMeasurementRouter& router() const { return *m_router; }
	const estimator::IUpdateEngine& updateEngine() const { return *m_engine; }
	const estimator::IObjectMotionModel& objectMotionModel() const { return *m_motion; }
	const estimator::IStateLifecycle& stateLifecycle() const { return *m_lifecycle; }

	// --- results: documented in src/results/reader.h (egoPose, staticLandmarks, ...) --------
	mrpt::poses::CPosePDFGaussian getEgoPose() const override;
	std::vector<TStaticLandmarkEstimate> getStaticLandmarks() const override;
	std::vector<TStaticLandmarkEstimate> getDroppedStaticLandmarks() const override;
	std::vector<TObjectFeatureEstimate> getObjectFeatures() const override;
	/** The pose histories (xi: the motion since the first sighting, not the pose in the world). */
	std::map<int32_t, TObjectTrack> getObjectTracks() const override;
	/** The pose in the world at the newest pose in the state (throws for an unknown object). */
	std::optional<TObjectWorldPose> getObjectWorldPose(int32_t object) const;
	std::map<int32_t, TObjectWorldPose> getObjectWorldPoses() const;
	/** The object's velocity (object_model = cv | ctrv); empty without a velocity block (the
	 * paper's model, or before a cv object's second pose). Throws std::invalid_argument for an
	 * object the filter does not know. */
	std::optional<TObjectVelocity> getObjectVelocity(int32_t object) const;
	/** object_model = mm: the mode probabilities of every object with a velocity after this
	 * step's readings, in the order of objectModeNames() (empty for single models). */
	const std::map<int32_t, Eigen::VectorXd>& getObjectModeProbabilities() const;
	/** The modes of object_model (mm: stationary, cv, turn, manoeuvre; empty: a single model). */
	std::vector<std::string> objectModeNames() const override;
	/** feature_labels = boxes: the box tracks of the last step (src/router_context.h). */
	std::vector<TTrackedBox> trackedBoxes() const override;
	/** The typed state after the ego pose (blocks and where they are stored; of the whole
	 * state, like every getter below: with compressed entries, an expanded copy,
	 * src/state_store.h). */
	const estimator::CPaddedLayout& getLayout() const;
	/** The layout as MRPT's 2-dof slots (a 3-dof pose is ObjectPoseA + ObjectPoseB). */
	const std::vector<TSlot>& getSlots() const;
	/** Mean and reported covariance without pads, labels (results::stateWithoutPads). */
	void getStateWithoutPads(Eigen::VectorXd& x, Eigen::MatrixXd& P,
	                         std::vector<std::string>* labels = nullptr) const;
	std::vector<size_t> padIndices() const;  ///< the pad entries (for checks)
	const TStepReport& getLastStepReport() const override { return m_report; }
	/** fuse_landmarks_prob (src/modules/fusion.cpp): every fusion so far (record_dropped). */
	const std::vector<estimator::TFusionPair>& getFusedLandmarks() const;
	/** The capability modules the options enabled (doc/architecture.md "Capability modules"), in
	 * the order their hooks run; empty: the step calls no module hook. */
	std::vector<std::string> enabledModules() const;
	/** The module hook calls since reset() (0 with no module enabled). */
	size_t moduleHookCalls() const;
	/** The router's decisions about the last step's readings, in observation order. */
	const estimator::TRoutedStep& lastRoutedStep() const { return m_routed; }
	int stepCount() const { return m_step + 1; }
	/** Full mean / covariance including pads (MRPT's storage). */
	const KFVector& fullMean() const;
	const KFMatrix& fullCov() const;
	/** static_update = compressed: the global update of the working state (the estimate is
	 * unchanged, the landmarks' storage order is not; src/state_store.h). */
	void globalUpdate();
	/** Working storage size (with compressed entries; equals fullMean().size() otherwise) and
	 * the static landmarks kept out of it (static_update = compressed). */
	size_t workingDim() const { return m_xkk.size(); }
	size_t passiveLandmarks() const { return m_lifecycle->passiveCount(); }
	/** Cheap counts of the state after the last step (no expanded copy; dynslam-run's
	 * timing.csv): the static landmarks in it (working and passive) and the objects with at
	 * least one block in it. */
	size_t staticLandmarkCount() const { return m_staticBlock.size() + passiveLandmarks(); }
	size_t liveObjectCount() const;
	/** First-estimate Jacobians only (empty otherwise): the first estimate of static landmark
	 * `id`, i.e. its mean at the end of the step in which it was initialized. */
	std::optional<Eigen::Vector2d> firstEstimate(int32_t id) const;
	/** First-estimate Jacobians only (empty otherwise): the predicted ego pose x_{k|k-1} of the
	 * last step, recorded after the prediction and before the update. */
	std::optional<Eigen::Vector3d> lastPredictedEgo() const;
	/** The transition Jacobian F of the last step's prediction (Alg. 7; with first-estimate
	 * Jacobians, the modified one); empty if the prediction was skipped. */
	const std::optional<Eigen::Matrix3d>& lastTransitionJacobian() const { return m_lastF; }
	/** The prior gauge's N = d(state)/d(delta) and fullCov() + N Sigma_0 N^T (anchor) or
	 * fullCov() (prior), as every getter reports: src/gauge/prior_gauge.h. */
	Eigen::MatrixXd gaugeJacobian() const;
	Eigen::MatrixXd reportedCov() const;
	/** The odometry bias and its covariance (empty: none), src/modules/odometry_bias.h. */
	std::optional<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> getOdometryBias() const;

protected:
	/** State surgery: static landmarks become object features (src/modules/state_surgery.h). */
	void convertStaticLandmarks(const std::vector<estimator::TRoutedStep::TConversion>& c);
	/** Merge of object `from` into `into` (src/modules/state_surgery.h). */
	bool mergeObjects(int32_t from, int32_t into);

	// --- CKalmanFilterCapable hooks (bodies: src/mrpt_kalman_adapter.h) -------------
	void OnGetAction(KFArray_ACT& out_u) const override;
	void OnTransitionModel(const KFArray_ACT& in_u, KFArray_VEH& inout_x,
	                       bool& out_skipPrediction) const override;
	void OnTransitionJacobian(KFMatrix_VxV& out_F) const override;
	void OnTransitionNoise(KFMatrix_VxV& out_Q) const override;
	void OnGetObservationNoise(KFMatrix_OxO& out_R) const override;
	void OnGetObservationsAndDataAssociation(vector_KFArray_OBS& out_z,
	                                         std::vector<int>& out_data_association,
	                                         const vector_KFArray_OBS& in_all_predictions,
	                                         const KFMatrix& in_S,
	                                         const std::vector<size_t>& in_lm_indices_in_S,
	                                         const KFMatrix_OxO& in_R) override;
	void OnObservationModel(const std::vector<size_t>& idx_landmarks_to_predict,
	                        vector_KFArray_OBS& out_predictions) const override;
	void OnObservationJacobians(size_t idx_landmark_to_predict, KFMatrix_OxV& Hx,
	                            KFMatrix_OxF& Hy) const override;
	void OnSubstractObservationVectors(KFArray_OBS& A, const KFArray_OBS& B) const override;
	void OnPreComputingPredictions(const vector_KFArray_OBS& in_all_prediction_means,
	                               std::vector<size_t>& out_LM_indices_to_predict) const override;
	using Base::OnInverseObservationModel;
	void OnInverseObservationModel(const KFArray_OBS& in_z, KFArray_FEAT& out_yn,
	                               KFMatrix_FxV& out_dyn_dxv,
	                               KFMatrix_FxO& out_dyn_dhn) const override;
	void OnNewLandmarkAddedToMap(size_t in_obsIdx, size_t in_idxNewFeat) override;
	void OnNormalizeStateVector() override;

private:
	/** The enabled capability modules (src/modules/module_list.h; made by reset()). */
	std::unique_ptr<ekf::CModuleList> m_modules;
	friend struct ekf::TFilterAccess;
	friend struct ekf::TFilterView;
	std::unique_ptr<ekf::CPriorGauge> m_gauge;        ///< prior_gauge (made by the constructor)
	std::unique_ptr<ekf::CStateStore> m_store;        ///< the state's lifecycle in the filter
	std::unique_ptr<ekf::CMrptKalmanAdapter> m_mrpt;  ///< MRPT's hooks and MRPT's update
	std::optional<Eigen::Matrix3d> m_lastF;           ///< F of the last prediction
	/** Whether the map holds nothing but the odometry bias block (src/modules/odometry_bias.h). */
	bool mapEmpty() const;

	friend class CMrptUpdateEngine;
	/** Alg. 7: the ego prediction by ekf::propagate (skipped on an empty map if
	 * skip_prediction_on_empty_map); with first-estimate Jacobians, linearised at the last
	 * step's x_{k|k-1} (src/modules/first_estimates.h). */
	void propagateEgo();
	/** Alg. 5 by the update engine, with the tracked static readings of the step. */
	void staticUpdate();
	estimator::TUpdateContext updateContext() const;
	/** What a step adds and drops, before it is written to the state: the new features as an
	 * augmentation a of the current state, the object poses as an augmentation b of the state
	 * extended by a (pads included), their blocks, and the blocks to remove, indexed in the
	 * layout extended by `blocks`. */
	struct TPending
	{
		ekf::Augmentation a, b;
		std::vector<estimator::TBlock> blocks;
		std::vector<size_t> remove;
	};
	/** The layout of the state extended by the plan (written into m_ext, valid until the next
	 * call or commit). */
	const estimator::CPaddedLayout& extendedLayout(const TPending& plan);
	void planFeatures(TPending& plan);     // Alg. 3: new static landmarks, objects
	void planObjectPoses(TPending& plan);  // Alg. 4, on the state extended by plan
	void planDrops(TPending& plan);        // drop policies, recording what they drop
	/** Writes plan to the state: x, P (one rewrite; reallocated only if the size changes) and
	 * the slot tables; clears plan. */
	void commit(TPending& plan);
	void applyObjectMotion();  // the object motion model's pseudo-measurements (Alg. 6)
	// The object-centric motion models (cv, ctrv, ca, mm): src/modules/object_motion.h.
	/** The whole state's layout, mean and covariance: the working state's storage, or its
	 * expanded copy (src/state_store.h). */
	struct TStateRef
	{
		const estimator::CPaddedLayout& layout;
		Eigen::Ref<const Eigen::VectorXd> x;
		Eigen::Ref<const ekf::RowMatrixXd> P;
	};
	TStateRef wholeState() const;

	/** Per-step scratch that keeps its capacity between steps (doc/results/performance.md, section
	 * 16, sixth round): the extended layout, the plan, commit's drop flags and mean. */
	estimator::CPaddedLayout m_ext;
	TPending m_plan;
	std::vector<bool> m_dropFlags;
	std::vector<double> m_xScratch;
	std::vector<Eigen::Vector2d> m_zScratch;
	std::vector<int32_t> m_idScratch, m_idScratch2;

	/** Rebuilds what is derived from the layout: the slot view and the static-landmark index. */
	void onLayoutChanged();
	/** The slot view of `layout` (and its statics), results::slotsOf (src/results/reader.h). */
	static void slotsOf(const estimator::CPaddedLayout& layout, std::vector<TSlot>& slots,
	                    std::vector<std::pair<int32_t, size_t>>* statics);

	// the seams (doc/architecture.md)
	std::unique_ptr<estimator::IMeasurementRouter> m_router;
	std::unique_ptr<estimator::IUpdateEngine> m_engine;
	std::unique_ptr<estimator::IObjectMotionModel> m_motion;
	std::unique_ptr<estimator::IStateLifecycle> m_lifecycle;
	bool m_userRouter = false, m_userEngine = false, m_userMotion = false;  ///< set by setX()
	bool m_userLifecycle = false;
	bool m_engineGated = true;  ///< the update context carries the gate (outlier_method's caps)
	/** reset(): the seams from their registries (estimator/seam_registries.h) and the options,
	 * except those set by setX(); throws std::invalid_argument on a combination that cannot work.
	 */
	void makeSeams();
	estimator::CDropPolicy m_drop;
	void forgetStatic(int32_t id);  ///< a static landmark left the state (drop policy, surgery)

	// inputs of the current step
	estimator::TStepInput m_in;
	estimator::TRoutedStep m_routed;

	// slot table and indices
	estimator::CPaddedLayout m_layout;  ///< the typed state after the ego (commit() writes it)
	std::vector<TSlot> m_slots;         ///< derived: the layout as MRPT's 2-dof slots
	std::map<int32_t, size_t> m_staticBlock;  ///< derived: landmark ID -> block
	std::vector<TStaticLandmarkEstimate> m_droppedStatic;
	int m_step = -1;
	TStepReport m_report;
	bool m_failed = false;  ///< a step threw midway: refuse to go on until reset()
	// The covariance (doc/results/performance.md, section 9): the filter works on m_cov, a buffer
	// that keeps its capacity; MRPT's m_pkk is a copy brought up to date by syncPkk() when it is
	// read (fullCov(), MRPT's update engine).
	ekf::CSquareBuffer m_cov;
	mutable bool m_pkkStale = false;  ///< m_pkk differs from m_cov
	uint64_t m_stateVersion = 0;      ///< changes with every write of the working state
	/** The working covariance (marks m_pkk stale and the state store's expanded copy old). */
	ekf::CSquareBuffer::View cov()
	{
		m_pkkStale = true;
		++m_stateVersion;
		return m_cov.view();
	}
	ekf::CSquareBuffer::ConstView cov() const { return m_cov.view(); }
	/** Copies m_cov to MRPT's m_pkk if it changed since the last copy. */
	void syncPkk() const;
	/** Resizes m_cov to n x n and writes P into it. */
	void setCov(const Eigen::Ref<const ekf::RowMatrixXd>& P);
};
}  // namespace dynslam
