#pragma once
/** @file CAlg1Backend.h
 * Alg. 1 of the paper (dynamic EKF-SLAM as iterative optimization), driven like
 * CDynamicKFSLAM2D: one (action, sensory frame) pair per step, the same step order and the
 * same bookkeeping, but every step is a Gauss-Newton or marginalization step on a running
 * cost (framework/running_cost.h) instead of a Kalman-filter formula:
 *
 *  1. propagation (Alg. 7, Theorem A.5): add x_t with the odometry residual, marginalize
 *     x_{t-1} (a zero-covariance action, e.g. the rawlog's ACT_0, is the exact change of
 *     variables x_t = x_{t-1} (+) u, the limit of the marginalization);
 *  2. static update (Alg. 5, Theorem A.3): measurement residuals of tracked landmarks, GN;
 *  3. static augmentation (Alg. 3, Theorem A.1): new landmarks at l(x, z), GN;
 *  4. object-feature augmentation (Alg. 3): time-0 features of new objects, time-t features;
 *  5. object-pose augmentation (Alg. 4, Theorem 4.1) per object, GN (pose-space residual by
 *     default, the exact equivalent of Alg. 4; feature_space selects the paper's form);
 *  6. smoothing (Alg. 6, Theorem 4.2), optional, GN;
 *  7. drops (time-t features, old object poses, unseen static landmarks): marginalization
 *     (deleting rows and columns of a covariance is marginalizing the Gaussian).
 * With an object-centric model (object_model = cv | ctrv, issue 13; framework/
 * object_motion_terms.h) also: after 1, every object with a velocity is predicted (motion term
 * from (xi, v) at t-1 to t, then (xi, v) at t-1 marginalized); after 2, its sightings are
 * measurement terms of ego, pose and body-frame features, one GN step per object (with the
 * model's gate); after 6, a new object's velocity is added with its initialisation term (GN).
 * With object_model = mm the motion term is the modes' moment-matched mixture, weighted by
 * the mode probabilities after the step's readings (estimator::CObjectModes), as in the EKF.
 * The same steps as the EKF's, so Alg. 1 equals it (tests/framework/alg1_equivalence_test.cpp).
 * After every GN step the cost is replaced by ||x - mu||^2_{J^T J} (Alg. 1: "cost <- ...").
 * The state is kept in information form; covariances are computed when asked for. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/estimator/drop_policy.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/object_modes.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/framework/TBackendOptions.h>
#include <dynslam/framework/running_cost.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dynslam::framework
{
class CAlg1Backend : public ISlamBackend
{
public:
	/** Throws std::invalid_argument if the options are invalid (validate()). */
	explicit CAlg1Backend(const TBackendOptions& opts);
	void reset();
	void processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
	                              const mrpt::obs::CSensoryFrame::Ptr& SF) override;
	std::string name() const override { return "alg1"; }
	mrpt::poses::CPosePDFGaussian getEgoPose() const override;
	std::vector<TStaticLandmarkEstimate> getStaticLandmarks() const override;
	std::vector<TStaticLandmarkEstimate> getDroppedStaticLandmarks() const override;
	std::vector<TObjectFeatureEstimate> getObjectFeatures() const override;
	std::map<int32_t, TObjectTrack> getObjectTracks() const override;
	const TStepReport& getLastStepReport() const override { return m_report; }
	/** The modes of object_model (mm: stationary, cv, turn, manoeuvre; empty: a single model). */
	std::vector<std::string> objectModeNames() const override;

	/** Mean, covariance and labels of the whole state in storage order; the labels are those
	 * of CDynamicKFSLAM2D::getStateWithoutPads (e.g. "ego.x", "lm3.y", "obj1.f2.t0.x",
	 * "obj1.xi7.dtheta"), so both can be compared entry by entry. */
	void getLabelledState(Eigen::VectorXd& x, Eigen::MatrixXd& P,
	                      std::vector<std::string>& labels) const;
	const CRunningCost& cost() const { return m_cost; }
	const TBackendOptions& options() const { return m_opts; }
	const estimator::IMeasurementRouter& router() const { return *m_router; }
	/** The seams (doc/architecture.md): another router or object motion model than the
	 * options'; kept by reset(). Call reset() after setting one. */
	void setRouter(std::unique_ptr<estimator::IMeasurementRouter> r);
	void setObjectMotionModel(std::shared_ptr<const estimator::IObjectMotionModel> m);
	int stepCount() const { return m_step + 1; }

private:
	TGaussNewtonResult gnAndCollapse();
	void propagate(const estimator::TStepInput& in);
	void staticSteps(const estimator::TRoutedStep& in);
	void objectFeatureAugmentation(const estimator::TRoutedStep& in);
	void objectPoseAugmentation();
	void objectMotion();  // the object motion model's pseudo-measurements (Alg. 6)
	void drops();
	// object-centric models (CAlg1Backend_objects.cpp; nothing with the paper's models)
	bool objectCentric() const;
	/** object_model from its registry (estimator::objectMotionModels(); cv's gate from
	 * cv_gate); std::invalid_argument for a model or an EKF-only cv key the framework does not
	 * implement. */
	static std::shared_ptr<const estimator::IObjectMotionModel> makeMotionModel(
	    const TModelOptions& o);
	/** With a multiple-model object_model, the mixture's prediction (CObjectMixtureMotionTerm)
	 * weighted by the mode probabilities after the step's readings of the object. */
	void predictObjects(const estimator::TRoutedStep& in);
	/** object_model = mm: log L_j of obj's readings in `in` under each mode's prediction of its
	 * [pose; velocity] (xi, v); empty without readings (the EKF's modeLogLikelihoods). */
	Eigen::VectorXd modeLogLikelihoods(int32_t obj, const TVarKey& xi, const TVarKey& v,
	                                   const estimator::TRoutedStep& in,
	                                   const estimator::TModePredictions& pred) const;
	estimator::CObjectModes m_modes;  ///< object_model = mm: per object
	void objectFeatureUpdates(const estimator::TRoutedStep& in);
	void initObjectVelocities();
	bool hasVelocity(int32_t obj) const { return m_velocitySince.count(obj) > 0; }
	Eigen::MatrixXd marginalCov(const TVarKey& k) const;
	/** prior_gauge = anchor (doc/framework.md): x_0 is an exact constraint (no prior term) until
	 * the first odometry with a non-zero covariance gives the ego its marginal G Sigma_u G^T
	 * (the running cost has no term before). gaugeTerm: the output term J Sigma_0 J^T of a
	 * variable of `kind` with value v (zero with prior_gauge = prior), models/gauge.h. */
	void propagateAnchored(const Eigen::Vector3d& u, const Eigen::Matrix3d& Su);
	Eigen::MatrixXd gaugeTerm(VarKind kind, const Eigen::VectorXd& v) const;
	bool m_anchorPending = false;  ///< anchor: the ego is still exactly x_0 (+) the odometry
	/** anchor, while pending: the ego's exact value; it is then no variable of the running cost,
	 * and the terms that read it are conditioned on it (addTerm). */
	Eigen::Vector3d m_fixedEgo = Eigen::Vector3d::Zero();
	Eigen::Vector3d egoValue() const
	{
		return m_anchorPending ? m_fixedEgo : Eigen::Vector3d(m_cost.value(m_ego));
	}
	void addTerm(const CTermPtr& t);
	bool isTimeT(const TVarKey& k) const;

	TBackendOptions m_opts;
	CRunningCost m_cost;
	TVarKey m_ego;
	int m_step = -1;
	Eigen::Vector3d m_sensor = Eigen::Vector3d::Zero();  ///< the step's sensor pose on the robot
	std::unique_ptr<estimator::IMeasurementRouter> m_router;
	std::shared_ptr<const estimator::IObjectMotionModel> m_motion;
	bool m_userRouter = false, m_userMotion = false;
	estimator::CDropPolicy m_drop;
	std::vector<TStaticLandmarkEstimate> m_droppedStatic;
	std::vector<TVarKey> m_newTimeT;         ///< time-t features added this step, observation order
	std::map<int32_t, int> m_velocitySince;  ///< object -> step its velocity was added
	TStepReport m_report;
};
}  // namespace dynslam::framework
