#pragma once
/** @file odometry_bias_options.h
 * Online odometry bias estimation (issue 17 item 2): odometry_bias in [DynamicKFSLAM], its
 * parameters in section [OdometryBias] (odometry_dt, bias_*; dynslam/common/model_keys.h); the
 * model is dynslam/core/models/odometry_bias.h, the state block estimator::BlockKind::OdometryBias
 * (doc/state-layout.md). Part of TModelOptions (dynslam/common/model_options.h). */
#include <dynslam/core/ekf_odometry_bias.h>
#include <mrpt/config/CConfigFileBase.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace dynslam
{
struct TOdometryBiasOptions
{
	/** odometry_bias = none (default: no bias block, the filter of before, unchanged) | rate
	 * (b_w, 1 entry) | rate_scale (b_w and the translation scale error s, 2 entries). */
	std::string mode = "none";
	/** Required when mode != none: the prior std of b_w [rad/s] (> 0) and its random-walk
	 * density [rad/s/sqrt(s)] (>= 0: the variance of b_w grows by rate_rw^2 dt per step). */
	double rate_std0 = 0, rate_rw = 0;
	/** Required for rate_scale: the prior std of s [-] (> 0), its random walk [1/sqrt(s)]. */
	double scale_std0 = 0, scale_rw = 0;
	/** Required when mode != none: the step duration [s] (> 0) used when the actions'
	 * timestamps give none (the first step, missing or non-increasing timestamps). */
	double odometry_dt = 0;

	bool enabled() const { return mode != "none"; }
	int dim() const { return mode == "rate_scale" ? 2 : 1; }
	/** The block's random walk (index set by the filter). */
	ekf::TOdometryBiasBlock block(int index) const;
	/** The prior covariance of the bias block (dim x dim, diagonal). */
	Eigen::MatrixXd prior() const;

	/** Reads odometry_bias from [core] and, when enabled, the keys of [OdometryBias]; throws
	 * std::invalid_argument naming [section] key. */
	void load(const mrpt::config::CConfigFileBase& c, const std::string& core);
	/** The section [OdometryBias] with its keys when enabled (odometry_bias itself is dumped
	 * with the core keys); nothing when off. */
	void dump(std::ostream& out) const;
};
}  // namespace dynslam
