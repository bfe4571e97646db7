#pragma once
/** @file CMrptUpdateEngine.h
 * MRPT's own update (CKalmanFilterCapable::runOneKalmanIteration with the prediction skipped:
 * kfEKFNaive or kfEKFAlaDavison as KF_options.method says) as an update engine of
 * CDynamicKFSLAM2D (static_update = mrpt). MRPT is handed only the tracked static landmarks;
 * new ones are augmented by the filter with the step's other new entries. */
#include <dynslam/estimator/update_engine.h>

namespace dynslam
{
class CDynamicKFSLAM2D;

class CMrptUpdateEngine : public estimator::IUpdateEngine
{
public:
	explicit CMrptUpdateEngine(CDynamicKFSLAM2D& kf) : m_kf(kf) {}
	std::string name() const override { return "mrpt"; }
	/** x and P must be the filter's own storage (MRPT updates it in place). */
	estimator::TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                                const std::vector<estimator::TStaticObservation>& obs,
	                                const estimator::TUpdateContext& ctx) override;
	/** MRPT updates the filter's own storage (m_xkk, m_pkk) through its hooks, whose slot table
	 * has no compressed entries: no lifecycle that rewrites the storage (a clear error in
	 * CDynamicKFSLAM2D::reset(); static_update = mrpt cannot name one anyway). */
	bool updatesGivenState() const override { return false; }

private:
	CDynamicKFSLAM2D& m_kf;
};
}  // namespace dynslam
