#pragma once
/** @file compressed_state.h
 * The exact compressed EKF (Guivant & Nebot, IEEE T-RA 2001; Knight, Davison & Reid 2001) as two
 * state rewrites, pure Eigen (doc/state-layout.md, "Compressed state").
 *
 * Split the state into an active part A (the ego, the objects, the static landmarks near the
 * robot) and a passive part B (static landmarks left behind). Every step of the EKF that touches
 * only A (prediction of the ego, updates whose H is zero on B, augmentations whose Jacobian is
 * zero on B, drops of A entries, object steps) changes the rest of the Gaussian linearly:
 *   cov(A, B) <- T cov(A, B),  cov(B, B) <- cov(B, B) - cov(B, A) M cov(A, B),
 *   x_B <- x_B + cov(B, A) v
 * for some T, M, v made of A's quantities only. Compression replaces B by m0 = |A| "compressed"
 * entries C with x_C = 0, cov(A, C) = I, cov(C, C) = 0 and stores (x_B, cov(B, B), cov(A, B)) as
 * they are. The EKF then runs on (A, C) unchanged: C is a state entry no model touches, so at
 * any later time
 *   cov(A', C) = Phi,  cov(C, C) = -Psi,  x_C = beta
 * are exactly Guivant & Nebot's accumulated matrices (A' = A as it is now: rows of entries added
 * since are the augmentation Jacobians times Phi, dropped rows are gone), and the global update
 * is
 *   x_B = x_B0 + cov(A,B)0^T beta,  cov(A', B) = Phi cov(A,B)0,
 *   cov(B, B) = cov(B,B)0 + cov(A,B)0^T cov(C,C) cov(A,B)0.
 * A later compression makes the earlier level's C entries passive along with new landmarks
 * (nested levels), so a compression costs O((|A| + |C|)^2 |A|) whatever the map size; the global
 * update unwinds every level, O(n^2 |A|). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/estimator/state_layout.h>

#include <Eigen/Core>
#include <vector>

namespace dynslam::estimator
{
/** One compression: the passive blocks as they were when they were taken out of the state. */
struct TPassiveLevel
{
	int level = 0;
	std::vector<TBlock> blocks;  ///< in storage order (landmarks, and the previous level's C)
	Eigen::VectorXd x;           ///< their storage entries' mean (p, pads included)
	Eigen::MatrixXd P;           ///< their covariance, p x p
	Eigen::MatrixXd cross;       ///< cov(active then, passive): m0 x p
	int m0 = 0;                  ///< storage entries active at compression (ego included)
};

/** Takes the flagged blocks (the Compressed blocks of the previous level among them, if any)
 * out of the state (x, P, layout): they are returned as level `level`; the new state (xo, Po,
 * layout) is the kept entries (in order) followed by the level's Compressed blocks (m0 entries
 * plus one unused, a pair per block) with mean 0, cov(kept, C) = [I 0], cov(C, C) = 0. */
TPassiveLevel compressState(const Eigen::Ref<const Eigen::VectorXd>& x,
                            const Eigen::Ref<const ekf::RowMatrixXd>& P, CPaddedLayout& layout,
                            const std::vector<bool>& passive, int level, Eigen::VectorXd& xo,
                            ekf::RowMatrixXd& Po);

/** The global update: brings every level's passive blocks up to date from the accumulated
 * matrices held by the state's Compressed entries (levels in the order they were made, the last
 * one's C blocks in the state) and writes the full state, its blocks in creation order
 * (TBlock::seq: the full EKF's storage order), the Compressed blocks removed. Clears `levels`. */
void expandState(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout,
                 std::vector<TPassiveLevel>& levels);
}  // namespace dynslam::estimator
