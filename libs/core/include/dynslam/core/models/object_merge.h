#pragma once
/** @file object_merge.h
 * Merging an object N into an object L (classify_merge_linked, doc/results/classification.md
 * "Merging a linked object"): N's features, kept in N's body frame, are re-expressed in L's body
 * frame,
 *
 *     f'_k = g_L^-1(xi_L, g_N(xi_N, f^N)_k),
 *
 * i.e. f^L = p_L^-1 (+) p_N (+) f^N with the pose maps of models/object_pose.h: g(xi, f) =
 * R(dtheta) (f - c0) + c0 + (dx, dy) (rotation about the time-0 centroid c0 of the object's
 * founders), g^-1(xi, w) = R(dtheta)^T (w - c0 - (dx, dy)) + c0; for a translation-only pose
 * (2 entries) g(xi, f) = f + xi. N without a pose (merged at its first sighting, when its f^N are
 * world points) is xi_N = the identity (an empty vector). c0_L is the centroid of L's founders'
 * f_0 and c0_N that of the first foundersN columns of f^N: both are state entries, so both are
 * inputs of the Jacobian.
 *
 * Input vector (the order of J_out_in's columns): [xi_L (dL); vec(f0L) (2 nL); xi_N (dN);
 * vec(fN) (2 m)], dL in {2, 3}, dN in {0, 2, 3}; with dL = 2, f0L may be empty (c0_L unused). */
#include <Eigen/Core>

namespace dynslam::models
{
/** Returns f' (2 x m) and J_out_in (2m x (dL + 2 nL + dN + 2m)). Throws std::invalid_argument on
 * a wrong size (dL = 3 with nL = 0, foundersN outside [1, m] with dN = 3). */
Eigen::Matrix2Xd mergeObjectFeatures(const Eigen::VectorXd& xiL, const Eigen::Matrix2Xd& f0L,
                                     const Eigen::VectorXd& xiN, const Eigen::Matrix2Xd& fN,
                                     int foundersN, Eigen::MatrixXd* J_out_in = nullptr);
}  // namespace dynslam::models
