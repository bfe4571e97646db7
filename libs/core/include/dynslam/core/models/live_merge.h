#pragma once
/** @file live_merge.h
 * The velocity part of the test that two live objects A and B move as one rigid body
 * (classify_merge_live with object_model = cv | ctrv, doc/results/classification.md "Merging two
 * live objects"). An object's velocity is that of its reference point p = c0 + (dx, dy) (the
 * centroid c0 of its founders' body-frame features moved by its pose; one founder: that feature),
 * with the turn rate omega for a 3-dof pose. If B is rigidly attached to A, B's reference point
 * moves with A's twist:
 *
 *     r_xy = v_B - v_A - omega_A perp(p_B - p_A),   perp(x, y) = (-y, x),
 *     r_w  = omega_B - omega_A                      (only if B has a 3-dof pose),
 *
 * and r = 0. A must have a 3-dof pose (a translation-only A has no turn rate: two translation-only
 * objects are never merged, the caller decides).
 *
 * Input vector (the order of J_out_in's columns): [xi_A (3); vec(f0A) (2 nA); v_A (3);
 * xi_B (dB); vec(f0B) (2 nB); v_B (dB)], dB in {2, 3}, nA >= 1, nB >= 1 (dB = 2: nB = 1). */
#include <Eigen/Core>

namespace dynslam::models
{
/** Returns r (dB entries) and J_out_in (dB x (6 + 2 nA + 2 dB + 2 nB)). Throws
 * std::invalid_argument on a wrong size. */
Eigen::VectorXd rigidVelocityResidual(const Eigen::Vector3d& xiA, const Eigen::Matrix2Xd& f0A,
                                      const Eigen::Vector3d& vA, const Eigen::VectorXd& xiB,
                                      const Eigen::Matrix2Xd& f0B, const Eigen::VectorXd& vB,
                                      Eigen::MatrixXd* J_out_in = nullptr);
}  // namespace dynslam::models
