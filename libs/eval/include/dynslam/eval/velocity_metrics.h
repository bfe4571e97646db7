#pragma once
/** @file velocity_metrics.h
 * Object velocity errors of the filters with a velocity state (object_model = cv | ctrv; issue
 * 13; doc/metrics.md "Object velocity"). Pure Eigen.
 *
 * The estimate: the velocity recorded with an object pose (TObjectPoseEstimate::velocity), the
 * world-frame velocity (vx, vy) of the object's reference point c0 + (dx, dy) and, for 3-dof
 * poses, the turn rate omega (models/object_motion.h). The truth at step k: the central
 * difference of the true pose, (xi_{k+1} - xi_{k-1}) / (t_{k+1} - t_{k-1}) (dtheta difference
 * wrapped), one-sided at the ends of the object's finite truth; exact for a constant velocity,
 * otherwise off by O(dt^2) times the rate of change of the acceleration. Estimates of objects
 * not in the truth, or at steps without two finite true poses around them, are skipped
 * (counted). */
#include <dynslam/eval/estimates.h>
#include <dynslam/io/ground_truth.h>

#include <cstdint>
#include <map>
#include <optional>

namespace dynslam::eval
{
struct TVelocityErrors
{
	size_t n = 0;              ///< velocity estimates scored
	size_t n_omega = 0;        ///< of these, with a turn rate (3-dof poses)
	size_t skipped = 0;        ///< velocity estimates without a truth to compare with
	double speed_rmse = kNaN;  ///< RMSE of |v_est - v_true| over (vx, vy) [m/s]
	double omega_rmse = kNaN;  ///< RMSE of the turn-rate error [rad/s]
	/** Sum of the NEES e^T P^-1 e of the scored velocities over the sum of their dof (2 or 3);
	 * estimates with a covariance that is not positive definite are left out of it. */
	double anees = kNaN;
	std::map<int32_t, double> speed_rmse_per_object;
};

/** True velocity of object o at step k (see the file comment); nullopt without two finite true
 * poses at distinct times around k. 3 entries (vx, vy, omega). */
std::optional<Eigen::Vector3d> trueObjectVelocity(const io::TObjectGroundTruth& o,
                                                  const std::vector<double>& t, int k);

/** Scores every object pose estimate with a velocity; nullopt if the run has none. */
std::optional<TVelocityErrors> objectVelocityErrors(const io::TGroundTruth& gt,
                                                    const TRunEstimates& est);
}  // namespace dynslam::eval
