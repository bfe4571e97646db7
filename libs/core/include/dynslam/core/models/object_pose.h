#pragma once
/** @file object_pose.h
 * Moving-object pose map g^o and its inverse gamma (paper eq. (3), Alg. 4, Appendix C).
 *
 * An object has n features; f0 (2 x n) are their positions at the object's first sighting
 * (time 0) and ft their positions at time t. The pose xi = (dx, dy, dtheta) of the object at
 * time t relative to time 0 moves every feature by a rotation about the time-0 centroid c0
 * followed by a translation:
 *
 *     f_t,k = g^o(xi, f0)_k = R(dtheta) (f0_k - c0) + c0 + (dx, dy),   c0 = mean_k f0_k.
 *
 * gamma(f0, ft) is the closed-form least-squares inverse (2-D Wahba / Procrustes): with
 * centred points p_i = a_i - mean(a), q_i = b_i - mean(b), S = sum p.q, C = sum p x q:
 * dtheta = atan2(C, S) and (dx, dy) = mean(b) - R (mean(a) - c0) - c0. When only a subset of
 * the features is seen at time t, the fit uses that subset (a_i = f0 of the seen features),
 * while c0 stays the centroid of all n time-0 features, so xi keeps one meaning.
 *
 * A one-feature object has a translation-only pose xi = f_t - f_0 (2-dof).
 *
 * Vectorisation: a 2 x n feature matrix F is vec(F) = (F_x1, F_y1, F_x2, F_y2, ...), so
 * Jacobian columns 2k and 2k+1 belong to feature k. */
#include <Eigen/Core>
#include <vector>

namespace dynslam::models
{
/** g^o(xi, f0): returns f_t (2 x n). J_ft_xi: d vec(ft)/d xi (2n x 3); J_ft_f0:
 * d vec(ft)/d vec(f0) (2n x 2n). c0: the centroid of the first centroidCols columns (0: all;
 * see objectPoseInverse). */
Eigen::Matrix2Xd objectPoseMap(const Eigen::Vector3d& xi, const Eigen::Matrix2Xd& f0,
                               Eigen::MatrixXd* J_ft_xi = nullptr,
                               Eigen::MatrixXd* J_ft_f0 = nullptr, int centroidCols = 0);

/** gamma(f0, ft): closed-form 2-D Procrustes fit of the object pose.
 * @param f0 all n time-0 features (2 x n).
 * @param ft the m features seen at time t (2 x m).
 * @param seen seen[i] = column of f0 that ft's column i corresponds to (distinct); empty
 *        means all, in order (m == n).
 * @param Gamma1 out: d xi / d vec(f0) (3 x 2n).
 * @param Gamma2 out: d xi / d vec(ft) (3 x 2m).
 * @param centroidCols c0 is the centroid of the first centroidCols columns of f0 (0: all). An
 *        object's founders (its features at time 0) define c0; features that joined later
 *        (doc/results/classification.md, "Late joining") follow them and leave c0 unchanged.
 * @throws std::invalid_argument on inconsistent sizes or indices;
 * @throws std::domain_error when the rotation is undetermined: fewer than 2 seen features, or
 *         the seen features all coincide (at time 0 or at time t). Collinear features are
 *         fine in 2-D: they determine the rotation. */
Eigen::Vector3d objectPoseInverse(const Eigen::Matrix2Xd& f0, const Eigen::Matrix2Xd& ft,
                                  const std::vector<int>& seen = {},
                                  Eigen::MatrixXd* Gamma1 = nullptr,
                                  Eigen::MatrixXd* Gamma2 = nullptr, int centroidCols = 0);

/** Translation-only pose of a one-feature object: xi = ft - f0, with Gamma1 = -I, Gamma2 = I. */
Eigen::Vector2d objectTranslationInverse(const Eigen::Vector2d& f0, const Eigen::Vector2d& ft,
                                         Eigen::Matrix2d* Gamma1 = nullptr,
                                         Eigen::Matrix2d* Gamma2 = nullptr);
}  // namespace dynslam::models
