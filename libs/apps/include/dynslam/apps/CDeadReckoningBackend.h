#pragma once
/** @file CDeadReckoningBackend.h
 * The `odometry` row of dynslam-compare (issue 31): dead reckoning. The ego pose is the
 * composition of the steps' odometry increments, x_{k+1} = x_k (+) u_k (models/se2.h, MRPT's
 * CPose2D composition), with the propagated covariance P_{k+1} = J_x P_k J_x^T + J_u U_k J_u^T;
 * no map, no objects, no readings used. The one step-input parser (dynslam/common/step_input.h)
 * reads the increments.
 *
 * Configuration: if the INI has [DynamicKFSLAM] (measurement_model set), its keys are loaded
 * (TModelOptions) and give the start x_0 = initial_pose, P_0 = Sigma_0, the increment's noise
 * (motion_noise = action: the action's covariance; config: Sigma_w) and the parser's options,
 * so the row is the dynamic EKF's prediction alone; otherwise x_0 = 0, P_0 = 0 and the action's
 * covariance. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/common/model_options.h>
#include <dynslam/estimator/readings.h>
#include <mrpt/config/CConfigFileBase.h>

#include <Eigen/Core>
#include <iosfwd>
#include <string>

namespace dynslam::apps
{
class CDeadReckoningBackend : public ISlamBackend
{
public:
	CDeadReckoningBackend();

	/** Loads [DynamicKFSLAM] if present (see the file comment) and resets. Throws
	 * std::invalid_argument naming section and key. */
	virtual void loadOptions(const mrpt::config::CConfigFileBase& ini);
	virtual void dumpOptions(std::ostream& out) const;
	/** Back to x_0, P_0, step 0. */
	virtual void reset();

	std::string name() const override { return "odometry"; }
	/** Parses the step (std::runtime_error on bad input, nothing changed) and composes. */
	void processActionObservation(const mrpt::obs::CActionCollection::Ptr& action,
	                              const mrpt::obs::CSensoryFrame::Ptr& SF) override;
	mrpt::poses::CPosePDFGaussian getEgoPose() const override;
	std::vector<TStaticLandmarkEstimate> getStaticLandmarks() const override { return {}; }
	std::vector<TStaticLandmarkEstimate> getDroppedStaticLandmarks() const override { return {}; }
	std::vector<TObjectFeatureEstimate> getObjectFeatures() const override { return {}; }
	std::map<int32_t, TObjectTrack> getObjectTracks() const override { return {}; }
	const TStepReport& getLastStepReport() const override { return m_report; }

	const Eigen::Vector3d& egoMean() const { return m_x; }
	const Eigen::Matrix3d& egoCov() const { return m_P; }

protected:
	/** Called after the ego of the step is composed, with the step's parsed input (the
	 * tracker_baseline row's hook). May throw; the ego is then already advanced. */
	virtual void onStep(const estimator::TStepInput& /*in*/) {}
	/** Number of steps processed so far (1 during the first onStep). */
	int steps() const { return m_report.step + 1; }

	TModelOptions m_model;
	bool m_hasModel = false;  ///< [DynamicKFSLAM] was loaded

private:
	Eigen::Vector3d m_x = Eigen::Vector3d::Zero();
	Eigen::Matrix3d m_P = Eigen::Matrix3d::Zero();
	TStepReport m_report;
};
}  // namespace dynslam::apps
