#pragma once
/** @file object_motion.h
 * (Internal to dynslam::ekf.) The object-centric motion models' module: object_model = cv, ctrv,
 * ca or mm (IObjectMotionModel::objectCentric(), velocityDim() > 0; issues 13, 28;
 * doc/state-layout.md "Object-centric motion models", "Multiple-model objects"). Made when the
 * filter's motion model is object-centric (the options' or one set by setObjectMotionModel); with
 * the paper's model (object_model = paper, paper_smoothing) it does not exist. Its hooks:
 *  - AfterPropagate: every object with a velocity is predicted over one step (its last pose is
 *    recorded first); object_model = mm: by the mixture of its modes, weighted by their
 *    probabilities after this step's readings (object_motion.cpp, object_motion_modes.cpp).
 *  - AfterStaticUpdate: every sighting of a feature of an object with a velocity is a
 *    measurement update of ego, pose and body-frame features, gated by the model's
 *    readingGate(); an object whose readings are all gated out for the model's count of steps is
 *    lost (object_motion_update.cpp).
 *  - AfterMotion(plan): a velocity block for each object whose first pose was added in this step
 *    (after a fallback: whose second pose since it was) (object_motion_velocity.cpp).
 *  - PlanDrops(plan): the fallback of the lost objects (cv_fallback_steps): their velocity and
 *    pose leave the state; after a re-initialisation, the older pose that gave the velocity
 *    (object_motion_velocity.cpp). After the object drop's.
 *  - ObjectForgotten(obj): an object dropped or merged away leaves the per-step sets.
 * Objects with a velocity have no time-t features: the facade's planFeatures asks
 * objectsWithVelocity(). */
#include <dynslam/estimator/object_modes.h>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "filter_module.h"

namespace dynslam::ekf
{
class CObjectMotionModule : public IFilterModule
{
public:
	std::string name() const override { return "object_motion"; }
	unsigned hooks() const override;
	void afterPropagate(TFilterAccess& a) override { predictObjects(a); }
	void afterStaticUpdate(TFilterAccess& a) override { objectFeatureUpdates(a); }
	void afterMotion(TFilterAccess& a, TPending& plan) override { planObjectVelocities(a, plan); }
	void planDrops(TFilterAccess& a, TPending& plan) override { planFallbacks(a, plan); }
	void objectForgotten(int32_t obj) override;

	/** The objects with a velocity block in layout L (their readings are updates, not time-t
	 * features). */
	static std::set<int32_t> objectsWithVelocity(const estimator::CPaddedLayout& L);
	/** object_model = mm: the mode probabilities of every object with a velocity after this
	 * step's readings (getObjectModeProbabilities). */
	const std::map<int32_t, Eigen::VectorXd>& modeProbabilities() const
	{
		return m_modes.probabilities();
	}
	/** Sets the poses' mode_probabilities from the modes' history (getObjectTracks). */
	void attachModeProbabilities(std::map<int32_t, TObjectTrack>& tracks) const;

private:
	/** An object's state blocks: its newest pose and its velocity (if any). */
	struct TObjectState
	{
		size_t pose = SIZE_MAX, velocity = SIZE_MAX;
	};
	static std::map<int32_t, TObjectState> objectStates(const estimator::CPaddedLayout& L);
	static std::vector<int> concat(std::vector<int> a, const std::vector<int>& b);

	void predictObjects(TFilterAccess& a);
	/** object_model = mm: predicts obj's s = x[idx] ([pose; velocity]) by the mixture of the
	 * modes (models/mode_mixture.h). */
	void predictObjectModes(TFilterAccess& a, int32_t obj, const std::vector<int>& idx);
	/** log L_j of obj's readings of this step under each mode's prediction (empty: none). */
	Eigen::VectorXd modeLogLikelihoods(TFilterAccess& a, int32_t obj, const std::vector<int>& idx,
	                                   const estimator::TModePredictions& pred) const;
	void objectFeatureUpdates(TFilterAccess& a);
	void planObjectVelocities(TFilterAccess& a, TPending& plan);
	void planFallbacks(TFilterAccess& a, TPending& plan);
	/** One object's velocity block and its prior v = G x + n, n ~ N(0, prior). */
	struct TVelocityInit
	{
		estimator::TBlock block;
		Eigen::MatrixXd G, prior;
		Eigen::VectorXd mean;
	};
	/** The velocity of obj from its pose block `pose` of this step; false: none yet. */
	bool velocityInit(TFilterAccess& a, int32_t obj, size_t pose, TVelocityInit& out);

	estimator::CObjectModes m_modes;  ///< object_model = mm: per object
	std::set<int32_t> m_lostNow;      ///< objects lost in this step (objectFeatureUpdates)
	std::set<int32_t> m_awaitingVel;  ///< lost objects that have no velocity yet
	std::set<int32_t> m_reinitNow;    ///< lost objects given a velocity in this step
};

/** The module if the filter's object motion model is object-centric (null otherwise). */
std::unique_ptr<CObjectMotionModule> makeObjectMotionModule(TFilterAccess& a);
}  // namespace dynslam::ekf
