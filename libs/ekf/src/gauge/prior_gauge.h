#pragma once
/** @file prior_gauge.h
 * (Internal to dynslam::ekf.) The prior gauge of CDynamicKFSLAM2D (prior_gauge, Sigma_0;
 * doc/state-layout.md "The prior gauge"). With prior_gauge = anchor the filter runs with the
 * initial pose as the gauge (its covariance P is relative to x_0) and the reported covariances
 * are P + N Sigma_0 N^T, N = d(state)/d(delta) the Jacobian of the state under a global rigid
 * transform delta about p0, the initial position (models/gauge.h); with prior_gauge = prior the
 * filter holds Sigma_0 in P and the output term is zero. A plain component, not a capability
 * module (doc/architecture.md "The prior gauge"): it takes part in no step, only in reset() and
 * in the results (src/results/). It reads prior_gauge and Sigma_0 from the filter's options at
 * each call, as the getters always did. */
#include <dynslam/common/model_options.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/estimator/state_layout.h>

#include <Eigen/Core>

namespace dynslam::ekf
{
class CPriorGauge
{
public:
	/** The gauge of the filter's options `o` (a reference: it must outlive the gauge). */
	explicit CPriorGauge(const TModelOptions& o) : m_options(o) {}
	/** reset(): p0 = the initial position; returns the ego's covariance at the start: zero with
	 * anchor (x_0 is the gauge), Sigma_0 with prior. */
	Eigen::Matrix3d reset();
	bool anchored() const { return m_options.prior_gauge_anchor; }
	/** The output term J Sigma_0 J^T of `block` (null: the ego pose) with mean `mean`; a zero
	 * matrix with prior_gauge = prior. */
	Eigen::MatrixXd term(const estimator::TBlock* block, const Eigen::VectorXd& mean) const;
	/** N of the state (x, layout) after the ego (fullMean().size() x 3; pad rows 0), for either
	 * gauge; `motion` tells a velocity block's parts (ca: [v; a]). */
	Eigen::MatrixXd jacobian(const estimator::CPaddedLayout& layout, const Eigen::VectorXd& x,
	                         const estimator::IObjectMotionModel& motion) const;
	/** The covariance reported outward: P with prior, P + N Sigma_0 N^T with anchor. */
	Eigen::MatrixXd reported(Eigen::MatrixXd P, const estimator::CPaddedLayout& layout,
	                         const Eigen::VectorXd& x,
	                         const estimator::IObjectMotionModel& motion) const;

private:
	const TModelOptions& m_options;
	Eigen::Vector2d m_origin = Eigen::Vector2d::Zero();  ///< p0 (reset())
};
}  // namespace dynslam::ekf
