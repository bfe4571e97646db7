#pragma once
/** @file state_view.h
 * (Internal to dynslam::ekf.) What the result readers (reader.h) and the prior gauge read of
 * CDynamicKFSLAM2D: a const view, the one friend of the facade for them. Everything a reader
 * reads of the filter goes through these members; none writes. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>

#include <vector>

namespace dynslam::ekf
{
class CPriorGauge;

struct TStateView
{
	/** A layout with its mean and covariance. */
	using TStateRef = CDynamicKFSLAM2D::TStateRef;
	const CDynamicKFSLAM2D& f;

	/** The working state: what the step updates (with static_update = compressed, without the
	 * landmarks held out of it). Ego, object and bias blocks are always in it. */
	TStateRef working() const { return {f.m_layout, f.m_xkk.asEigen(), f.m_cov.view()}; }
	/** The whole state: the working state, or its expanded copy while the lifecycle holds
	 * compressed entries (made on the first read after a change). */
	TStateRef whole() const { return f.wholeState(); }
	const TModelOptions& options() const { return f.options; }
	int step() const { return f.m_step; }
	const CPriorGauge& gauge() const { return *f.m_gauge; }
	const estimator::IObjectMotionModel& motion() const { return *f.m_motion; }
	/** The objects known to the router (poses and velocities dropped from the state included). */
	const estimator::CObjectRegistry& objects() const { return f.m_router->registry(); }
	/** The static landmarks dropped from the state, their last estimates (relative covariance). */
	const std::vector<TStaticLandmarkEstimate>& droppedStatic() const { return f.m_droppedStatic; }
	/** The recorded f_0 of the objects dropped by drop_object_after_unseen_steps (null: none). */
	const std::vector<TObjectFeatureEstimate>* droppedObjectFeatures() const;
};
}  // namespace dynslam::ekf
