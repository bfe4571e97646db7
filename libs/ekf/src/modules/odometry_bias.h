#pragma once
/** @file odometry_bias.h
 * (Internal to dynslam::ekf.) The odometry-bias module (odometry_bias = rate | rate_scale, issue
 * 17; its keys in [OdometryBias], dynslam/common/odometry_bias_options.h; the model
 * dynslam/core/models/odometry_bias.h). It owns the bias block, the first block of the state,
 * never dropped: reset() appends it with its prior (addBlock); the facade's prediction
 * (propagateEgo) calls stepDuration() every step and, unless the prediction is skipped,
 * propagate() instead of the plain ekf::propagate. No step hook. */
#include <dynslam/common/odometry_bias_options.h>

#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "filter_module.h"

namespace dynslam::ekf
{
class COdometryBiasModule : public IFilterModule
{
public:
	explicit COdometryBiasModule(const TOdometryBiasOptions& o) : m_options(o) {}
	std::string name() const override { return "odometry_bias"; }
	unsigned hooks() const override { return 0; }
	/** Appends the bias block with its prior (mean 0) to the empty map (reset()). */
	void addBlock(TFilterAccess& a) const;
	/** The step's duration: the actions' timestamp difference, else odometry_dt; 0 on the first
	 * step (the simulator's ACT_0 is a zero increment). Records the step's timestamp. */
	double stepDuration(double stamp, int step);
	/** Alg. 7 with the bias block's correction and random walk (ekf::propagateWithBias); the
	 * block's first entry at `index`; F: the transition Jacobian used. */
	void propagate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
	               const Eigen::Vector3d& u, const Eigen::Matrix3d& S, int index, double dt,
	               const Eigen::Vector3d* fejPrev, Eigen::Matrix3d& F) const;
	/** The bias estimate of the working state s, (b_w) or (b_w, s), and its covariance (empty if
	 * its first block is not the bias). */
	static std::optional<std::pair<Eigen::VectorXd, Eigen::MatrixXd>> estimate(
	    const TFilterView::TStateRef& s);

private:
	TOdometryBiasOptions m_options;
	double m_lastStamp = std::numeric_limits<double>::quiet_NaN();  ///< [s] (NaN: none)
};

/** The module if odometry_bias != none (null otherwise). */
std::unique_ptr<COdometryBiasModule> makeOdometryBiasModule(TFilterAccess& a);
}  // namespace dynslam::ekf
