#pragma once
/** @file filter_module.h
 * (Internal to dynslam::ekf.) The capability-module seam of CDynamicKFSLAM2D (issue 32 item 2,
 * doc/architecture.md "Capability modules"). A capability that only some configurations use
 * (landmark fusion, object drops, first-estimate Jacobians, linked and live merges, the
 * object-centric motion models) is a module:
 * it owns its members, is made by reset() only when its options enable it (module_list.cpp), and
 * names the hooks of the step it takes part in. The step calls the hooks of the enabled modules
 * only, in the order the modules were made:
 *
 *   route -> AfterRoute -> propagate -> AfterPropagate -> update -> AfterStaticUpdate ->
 *   augment -> motion model -> AfterMotion -> drops -> PlanDrops -> commit -> AfterCommit ->
 *   EndOfStep -> compression
 *
 * plus StaticForgotten whenever a static landmark leaves the state (drop policy, surgery) and
 * ObjectForgotten whenever an object does (object drop, merge).
 * Modules reach the filter's internals only through TFilterAccess, the one friend of the facade
 * for them: the list of what a module may read and write. The facade's other components (the
 * state store, MRPT's hooks, the router's context: src/) use it too, and TFilterView, its
 * read-only counterpart, from the facade's const functions. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/state_helper.h>

#include <cstdint>
#include <string>
#include <utility>

namespace dynslam::ekf
{
class CPriorGauge;
/** The hook points of the step (IFilterModule's virtual functions of the same names). */
enum class Hook : uint8_t
{
	AfterRoute,         ///< after the router's decisions, before the report copies them
	AfterPropagate,     ///< after the ego prediction (also when it was skipped)
	AfterStaticUpdate,  ///< after the static update (Alg. 5), before the augmentations
	AfterMotion,        ///< after the motion model's pseudo-measurements (if actsOnNewPoses())
	PlanDrops,          ///< after the drop policies planned theirs, before the commit
	AfterCommit,        ///< after the step's last commit (state surgery may commit again)
	EndOfStep,          ///< last, before the state's lifecycle compresses
	StaticForgotten,    ///< a static landmark left the state or became an object feature
	ObjectForgotten     ///< an object left the state (object drop) or the registry (merge)
};
constexpr size_t kHookCount = 9;
/** The bit of hook h in IFilterModule::hooks(). */
constexpr unsigned hookBit(Hook h) { return 1u << unsigned(h); }

/** The read-only access to the filter (a friend of CDynamicKFSLAM2D) of the components that the
 * facade's const functions call: the state store's expanded copy, MRPT's hooks, the router's
 * context and the box tracks. */
struct TFilterView
{
	using TStateRef = CDynamicKFSLAM2D::TStateRef;
	const CDynamicKFSLAM2D& f;

	const TModelOptions& options() const { return f.options; }
	int step() const { return f.m_step; }
	/** The step's parsed input: odometry, readings, sensor pose, boxes, time stamp. */
	const estimator::TStepInput& input() const { return f.m_in; }
	/** The working state: what the step updates (with static_update = compressed, without the
	 * landmarks held out of it). Ego, object and bias blocks are always in it. */
	TStateRef working() const { return {f.m_layout, f.m_xkk.asEigen(), f.m_cov.view()}; }
	/** The whole state: the working state, or its expanded copy while the lifecycle holds
	 * compressed entries (made on the first read after a change). */
	TStateRef whole() const { return f.wholeState(); }
	const CPriorGauge& gauge() const { return *f.m_gauge; }
	const estimator::IObjectMotionModel& motion() const { return *f.m_motion; }
	/** The objects known to the router (poses and velocities dropped from the state included). */
	const estimator::CObjectRegistry& objects() const { return f.m_router->registry(); }
	/** The static landmarks dropped from the state, their last estimates (relative covariance). */
	const std::vector<TStaticLandmarkEstimate>& droppedStatic() const { return f.m_droppedStatic; }
	/** The recorded f_0 of the objects dropped by drop_object_after_unseen_steps (null: none). */
	const std::vector<TObjectFeatureEstimate>* droppedObjectFeatures() const;
	/** The router (null only before the filter's first reset()). */
	const estimator::IMeasurementRouter* router() const { return f.m_router.get(); }
	const estimator::IStateLifecycle& lifecycle() const { return *f.m_lifecycle; }

	// the working state
	const estimator::CPaddedLayout& layout() const { return f.m_layout; }
	/** The layout as MRPT's 2-dof slots. */
	const std::vector<TSlot>& slots() const { return f.m_slots; }
	/** Landmark ID -> block of the static landmarks in the working state. */
	const std::map<int32_t, size_t>& staticBlocks() const { return f.m_staticBlock; }
	auto mean() const { return f.m_xkk.asEigen(); }
	Eigen::Vector3d ego() const { return {f.m_xkk[0], f.m_xkk[1], f.m_xkk[2]}; }
	ekf::CSquareBuffer::ConstView cov() const { return f.cov(); }
	/** Changes with every write of the working state (a step, a write of its covariance). */
	uint64_t stateVersion() const { return f.m_stateVersion; }
	/** Whether the map holds nothing but the bias block. */
	bool mapEmpty() const { return f.mapEmpty(); }
	/** The slot view of `layout`. */
	static void slotsOf(const estimator::CPaddedLayout& layout, std::vector<TSlot>& slots)
	{
		CDynamicKFSLAM2D::slotsOf(layout, slots, nullptr);
	}
};

/** The narrow access of the modules to the filter (a friend of CDynamicKFSLAM2D). Everything a
 * module reads or writes of the filter goes through these members. */
struct TFilterAccess
{
	using TPending = CDynamicKFSLAM2D::TPending;
	CDynamicKFSLAM2D& f;

	/** The read-only access (TFilterView). */
	TFilterView view() const { return {f}; }
	const TModelOptions& options() const { return f.options; }
	int step() const { return f.m_step; }
	TStepReport& report() { return f.m_report; }
	/** The step's parsed input: odometry, readings, sensor pose, boxes, time stamp. */
	const estimator::TStepInput& input() const { return f.m_in; }
	/** The sensor pose of the step's readings (robot frame). */
	const Eigen::Vector3d& sensorPose() const { return f.m_in.sensor_pose; }
	/** The router's decisions of the step (AfterRoute may change their routes and IDs). */
	estimator::TRoutedStep& routed() { return f.m_routed; }
	estimator::IMeasurementRouter& router() { return *f.m_router; }
	/** Whether the router was set by setRouter (not made from the options). */
	bool userRouter() const { return f.m_userRouter; }
	const estimator::IObjectMotionModel& motion() const { return *f.m_motion; }
	estimator::IObjectMotionModel& motion() { return *f.m_motion; }
	const estimator::IStateLifecycle& lifecycle() const { return *f.m_lifecycle; }
	/** The lifecycle for its calls that change what it holds (the state store only). */
	estimator::IStateLifecycle& lifecycle() { return *f.m_lifecycle; }
	estimator::CDropPolicy& dropPolicy() { return f.m_drop; }

	// the working state
	const estimator::CPaddedLayout& layout() const { return f.m_layout; }
	/** Landmark ID -> block of the static landmarks in the working state. */
	const std::map<int32_t, size_t>& staticBlocks() const { return f.m_staticBlock; }
	auto mean() { return f.m_xkk.asEigen(); }
	auto mean() const { return std::as_const(f.m_xkk).asEigen(); }
	Eigen::Vector3d ego() const { return {f.m_xkk[0], f.m_xkk[1], f.m_xkk[2]}; }
	/** The covariance for writing (marks MRPT's copy stale). */
	ekf::CSquareBuffer::View cov() { return f.cov(); }
	const ekf::CSquareBuffer& covBuffer() const { return f.m_cov; }
	/** The working layout for a change: relabelled blocks (state surgery), then layoutChanged();
	 * or a lifecycle's rewrite, then setWorkingState(). */
	estimator::CPaddedLayout& editLayout() { return f.m_layout; }
	/** Rebuilds what is derived from the layout (the slot view, the static-landmark index). */
	void layoutChanged() { f.onLayoutChanged(); }
	/** The state helper's augment (estimator::state::augment) on the working state: `block`
	 * appended with mean g, Jacobian J on x[in] and noise R (reset(): the odometry bias). */
	void augment(const estimator::TBlock& block, const Eigen::VectorXd& g,
	             const std::vector<int>& in, const Eigen::MatrixXd& J, const Eigen::MatrixXd& R)
	{
		Eigen::VectorXd x = f.m_xkk.asEigen();
		ekf::RowMatrixXd P = f.m_cov.view();
		estimator::state::augment(x, P, f.m_layout, block, g, in, J, R);
		setWorkingState(x, P);
	}
	/** Writes (x, P) as the working state after its layout changed (a lifecycle, augment). */
	void setWorkingState(const Eigen::VectorXd& x, const ekf::RowMatrixXd& P)
	{
		f.m_xkk.resize(size_t(x.size()));
		f.m_xkk.asEigen() = x;
		f.setCov(P);
		f.onLayoutChanged();
	}
	/** Sets the step of block b of the working layout (call layoutChanged() after). */
	void setBlockStep(size_t b, int step) { f.m_layout.setStep(b, step); }
	/** Wraps the state's angles (MRPT's OnNormalizeStateVector). */
	void normalize() { f.OnNormalizeStateVector(); }

	// operations of the facade
	/** The layout extended by plan (valid until the next call or commit). */
	const estimator::CPaddedLayout& extendedLayout(const TPending& plan)
	{
		return f.extendedLayout(plan);
	}
	void commit(TPending& plan) { f.commit(plan); }
	/** A static landmark left the state or became an object feature: the drop policy and the
	 * modules forget it. */
	void forgetStatic(int32_t id) { f.forgetStatic(id); }
	/** MRPT's runOneKalmanIteration (static_update = mrpt, src/mrpt_kalman_adapter.h) on MRPT's
	 * copy of the covariance, written back to the working covariance. */
	void runMrptIteration()
	{
		f.syncPkk();
		f.runOneKalmanIteration();
		f.setCov(f.m_pkk.asEigen());
		f.m_pkkStale = false;
	}
	/** A static landmark's last estimate joins the dropped ones (getDroppedStaticLandmarks). */
	void recordDroppedStatic(const TStaticLandmarkEstimate& e) { f.m_droppedStatic.push_back(e); }
	/** Object obj left the state: the ObjectForgotten hooks (module_list.cpp). */
	void objectForgotten(int32_t obj);
};

/** A capability module. Only the hooks named by hooks() are called. */
class IFilterModule
{
public:
	using TPending = TFilterAccess::TPending;
	virtual ~IFilterModule() = default;
	/** The module's name (CDynamicKFSLAM2D::enabledModules()). */
	virtual std::string name() const = 0;
	/** The hooks it takes part in: a bit per Hook (hookBit). */
	virtual unsigned hooks() const = 0;
	virtual void afterRoute(TFilterAccess&) {}
	virtual void afterPropagate(TFilterAccess&) {}
	virtual void afterStaticUpdate(TFilterAccess&) {}
	virtual void afterMotion(TFilterAccess&, TPending&) {}
	virtual void planDrops(TFilterAccess&, TPending&) {}
	virtual void afterCommit(TFilterAccess&) {}
	virtual void endOfStep(TFilterAccess&) {}
	virtual void staticForgotten(int32_t) {}
	virtual void objectForgotten(int32_t) {}
};
}  // namespace dynslam::ekf
