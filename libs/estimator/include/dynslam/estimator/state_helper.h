#pragma once
/** @file state_helper.h
 * The generic writers of the estimator's mean and covariance (the idea of OpenVINS'
 * StateHelper on the typed layout of state_layout.h): every change of (x, P) is one of
 *  - propagate: x[idx] <- f, P <- F P F^T + Q on the entries idx (F acts on idx only);
 *  - update: a Kalman update through an update engine (update_engine.h);
 *  - augment: a new block with mean g(x[in]), Jacobian J on x[in] and noise R;
 *  - marginalize: blocks leave the state (their mean and covariance entries dropped);
 *  - replace: x[out] <- g(x[in]), P <- T P T^T, T the identity but for the rows `out`, which are
 *    J on the columns `in` (state surgery, merges);
 *  - condition: the perfect constraint x[a] = x[b] (landmark fusion: a noise-free update on the
 *    difference; marginalize b afterwards).
 * Pure Eigen; tested against dense computations (tests/estimator/test_state_helper.cpp). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/estimator/state_layout.h>
#include <dynslam/estimator/update_engine.h>

#include <Eigen/Core>
#include <vector>

namespace dynslam::estimator::state
{
/** x[idx] <- f, P[idx,:] <- F P[idx,:], P[:,idx] <- P[:,idx] F^T, P[idx,idx] += Q
 * (ekf::predictSubset). F, Q: |idx| x |idx|. */
void propagate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
               const std::vector<int>& idx, const Eigen::VectorXd& f, const Eigen::MatrixXd& F,
               const Eigen::MatrixXd& Q);

/** The engine's update of (x, P) by the readings. */
TUpdateResult update(IUpdateEngine& engine, Eigen::Ref<Eigen::VectorXd> x,
                     Eigen::Ref<ekf::RowMatrixXd> P, const std::vector<TStaticObservation>& obs,
                     const TUpdateContext& ctx);

/** Appends `block` (block.dim entries, plus a pad if odd: mean 0, variance 1, no correlation)
 * to the layout and the state: its mean g, its covariance J P[in,in] J^T + R and its
 * cross-covariance J P[in,:] (J: dim x |in|, R: dim x dim). Throws std::invalid_argument on
 * sizes that do not match. */
void augment(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout, const TBlock& block,
             const Eigen::VectorXd& g, const std::vector<int>& in, const Eigen::MatrixXd& J,
             const Eigen::MatrixXd& R);

/** Removes the flagged blocks (one flag per block of `layout`) from the layout and the state. */
void marginalize(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout,
                 const std::vector<bool>& remove);

/** x[out] <- g, P <- T P T^T with T = I except T[out, :] = 0, T[out, in] = J (J: |out| x |in|;
 * `out` and `in` may overlap). The entries outside `out` keep their mean and their covariance
 * among themselves exactly; P stays exactly symmetric. Throws std::invalid_argument on sizes
 * that do not match. */
void replace(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
             const std::vector<int>& in, const std::vector<int>& out, const Eigen::VectorXd& g,
             const Eigen::MatrixXd& J);

/** Conditions (x, P) on the perfect constraint x[a] = x[b] (|a| = |b| = k, disjoint): the Kalman
 * update with H = [.. I_a .. -I_b ..], the reading 0 and no noise. With A = P[:, a] - P[:, b]
 * (n x k) and S = A[a, :] - A[b, :] = P_aa + P_bb - P_ab - P_ba: x <- x - A S^-1 (x[a] - x[b]),
 * P <- P - A S^-1 A^T (a rank-k update, O(n^2 k); P stays exactly symmetric). Afterwards x[a] =
 * x[b] and the rows a and b of P are equal (P is singular): marginalize one of them next (the
 * landmark fusion, landmark_fusion.h). Throws std::invalid_argument on sizes or overlapping
 * indices, std::runtime_error if S is not positive definite (nothing changed then). */
void condition(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
               const std::vector<int>& a, const std::vector<int>& b);
}  // namespace dynslam::estimator::state
