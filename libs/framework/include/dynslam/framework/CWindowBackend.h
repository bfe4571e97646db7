#pragma once
/** @file CWindowBackend.h
 * The back-ends of Section III as configurations of the framework (doc/backends.md): a
 * windowed (or full-horizon) smoother on a running cost, iterated Gauss-Newton to
 * convergence each step, with what it keeps, marginalizes and drops set by the kind:
 *  - vdo: everything kept over the whole horizon (ego poses, landmarks, object features at
 *    every time, object poses); feature-space object residual; sparse Cholesky;
 *  - dynaslam2: a sliding window of W ego poses; object poses added every step; the time-t
 *    object features are marginalized (or dropped) right after their step;
 *  - cubeslam: no object features in the window: a pose fit of each object's features in the
 *    sensor frame is the measurement of its body pose (CBodyPoseMeasurementTerm);
 *  - clusterslam_decoupled / clusterslam_semidecoupled: the static scene (ego poses,
 *    landmarks) is one cost, the objects another; the object cost sees the ego poses held at
 *    the static estimate (decoupled) or with the static cost's joint marginal as a prior
 *    (semi-decoupled: one-way coupling); nothing flows back into the static cost.
 * Ego poses older than the window are marginalized; object poses leave with them and are
 * recorded with their last estimate. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/estimator/drop_policy.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/framework/TBackendOptions.h>
#include <dynslam/framework/running_cost.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dynslam::framework
{
class CWindowBackend : public ISlamBackend
{
public:
	explicit CWindowBackend(const TBackendOptions& opts);
	void reset();
	void processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
	                              const mrpt::obs::CSensoryFrame::Ptr& SF) override;
	std::string name() const override { return m_opts.backend; }
	mrpt::poses::CPosePDFGaussian getEgoPose() const override;
	std::vector<TStaticLandmarkEstimate> getStaticLandmarks() const override;
	std::vector<TStaticLandmarkEstimate> getDroppedStaticLandmarks() const override;
	std::vector<TObjectFeatureEstimate> getObjectFeatures() const override;
	std::map<int32_t, TObjectTrack> getObjectTracks() const override;
	const TStepReport& getLastStepReport() const override { return m_report; }
	const CRunningCost& cost() const { return m_cost; }
	int lastIterations() const { return m_lastIterations; }
	/** The ego trajectory as the back-end finally holds it: the smoothed poses still in the
	 * window and, for those that left it, their estimate at marginalization (fixed-lag). */
	std::map<int, Eigen::Vector3d> finalTrajectory() const;

private:
	bool coupled() const;
	bool cube() const { return m_opts.backend == "cubeslam"; }
	CRunningCost& objectCost() { return coupled() ? m_cost : m_objCost; }
	const CRunningCost& objectCost() const { return coupled() ? m_cost : m_objCost; }
	void addObjects(const estimator::TRoutedStep& in, const TVarKey& ego);
	void addCubeObjects(const estimator::TRoutedStep& in, const TVarKey& ego);
	void linkEgoToObjectCost();
	void optimize(CRunningCost& c);
	void slideWindow();
	Eigen::Matrix2d pointCov(const Eigen::Vector2d& z) const;
	TObjectPoseEstimate poseEstimate(int32_t obj, int step) const;
	TGaussNewtonOptions gnOptions() const;

	TBackendOptions m_opts;
	CRunningCost m_cost, m_objCost;
	CTermPtr m_egoLink;  ///< clusterslam: the current prior on the ego copies in m_objCost
	int m_step = -1;
	Eigen::Vector3d m_sensor = Eigen::Vector3d::Zero();  ///< the step's sensor pose on the robot
	std::unique_ptr<estimator::IMeasurementRouter> m_router;
	std::shared_ptr<const estimator::IObjectMotionModel> m_motion;
	estimator::CDropPolicy m_drop;
	std::map<int32_t, Eigen::Matrix2Xd> m_body;  ///< cubeslam: time-0 features, robot frame
	std::vector<TStaticLandmarkEstimate> m_droppedStatic;
	std::map<int, Eigen::Vector3d> m_egoRecorded;
	TStepReport m_report;
	int m_lastIterations = 0;
};
}  // namespace dynslam::framework
