#pragma once
/** @file motion_metrics.h
 * Trajectory metrics beyond Table I (doc/metrics.md, section "Relative and object-motion
 * errors"), pure Eigen:
 *  - the ego relative pose error (RPE) over a fixed step gap (TUM/KITTI odometry style);
 *  - the object motion error in VDO-SLAM's form (Zhang et al. 2020): the error of each object's
 *    frame-to-frame rigid motion expressed in the object's body frame at k-1, translation [m]
 *    and rotation [rad];
 *  - the object position error: the world position of each object's rotation centre.
 *
 * Object poses xi = (dx, dy, dtheta) relative to the first sighting act on points as
 * G(xi) p = R(dtheta) (p - c0) + c0 + (dx, dy) (object_pose.h's g^o; c0 = the centroid of the
 * object's time-0 features). The object's body frame at step k is L_k = (c0 + d_k, dtheta_k)
 * (axes aligned with the world at the first sighting), so the world motion of its points is
 * H_k = L_k L_{k-1}^-1 = G(xi_k) G(xi_{k-1})^-1 and the body-frame motion is
 * M_k = L_{k-1}^-1 H_k L_{k-1} = L_{k-1}^-1 L_k, independent of where the world origin is (a
 * world-frame H would charge every heading error times the distance to the origin). Scored for
 * consecutive steps with a pose estimate and a finite truth; the estimate uses its own c0
 * (centroid of its f_0 estimates), the truth its own (centroid of the same features at
 * first_step). Error E = M_gt^-1 M_est: t_err = |t(E)|, r_err = |angle(E)|. Translation-only
 * objects (2-dof poses): M = translation by d_k - d_{k-1}, r_err not counted (their truth's
 * dtheta is ignored too).  */
#include <dynslam/eval/estimates.h>
#include <dynslam/io/ground_truth.h>

#include <cstdint>
#include <map>
#include <vector>

namespace dynslam::eval
{
/** RPE over the pairs (k, k + delta) with both ego estimates and the truth:
 * E = (gt_k^-1 gt_{k+delta})^-1 (est_k^-1 est_{k+delta}); RMSE of |t(E)| and of |angle(E)|. */
struct TRelativePoseError
{
	int delta = 0;
	size_t n = 0;
	double trans_rmse = kNaN, rot_rmse = kNaN;
};
TRelativePoseError relativePoseError(const io::TGroundTruth& gt,
                                     const std::vector<TEgoEstimate>& ego, int delta);

/** Errors of one object or pooled. */
struct TMotionError
{
	size_t n = 0;                               ///< frame-to-frame motions scored
	size_t n_rot = 0;                           ///< of these, with a rotation (3-dof poses)
	double trans_rmse = kNaN, rot_rmse = kNaN;  ///< [m], [rad]
	double trans_mean = kNaN, rot_mean = kNaN;  ///< [m], [rad] (VDO-SLAM reports means)
};

struct TObjectErrors
{
	std::map<int32_t, TMotionError> motion_per_object;
	TMotionError motion;  ///< all objects pooled
	size_t position_n = 0;
	double position_rmse = kNaN;  ///< [m] rotation centre in the world, all estimates pooled
	std::map<int32_t, double> position_rmse_per_object;
};

/** Object motion and position errors of a run. Pose estimates of objects or steps without a
 * finite truth, or of objects without f_0 estimates, are skipped. */
TObjectErrors objectErrors(const io::TGroundTruth& gt, const TRunEstimates& est);

/** Body-frame motion M = L_{k-1}^-1 L_k (x, y, theta) of a pose pair with rotation centre c0
 * (3-dof xi; for 2-dof pass dtheta = 0). */
Eigen::Vector3d bodyFrameMotion(const Eigen::Vector3d& xi_prev, const Eigen::Vector3d& xi_now,
                                const Eigen::Vector2d& c0);
}  // namespace dynslam::eval
