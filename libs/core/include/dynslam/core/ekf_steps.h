#pragma once
/** @file ekf_steps.h
 * The dynamic EKF's steps (paper Alg. 3-7) as dense functions on a Gaussian (mean x,
 * covariance P), independent of MRPT. CDynamicKFSLAM2D calls them on MRPT's m_xkk / m_pkk
 * (row-major, hence RowMatrixXd); the optimization framework and the tests call them on
 * their own matrices.
 *
 * Steps that add variables (augmentations) return the new mean entries and covariance blocks
 * (struct Augmentation) and leave the resize to the owner of the storage; steps that change
 * existing entries (updates, propagation) work in place. The ego pose is always x[0..2].
 *
 * Every function checks its arguments: state indices out of range throw std::out_of_range;
 * inconsistent sizes (P not matching x, Sigma_s not 2x2 or 3x3, several time-t features for a
 * one-feature object) throw std::invalid_argument. */
#include <dynslam/core/models/measurement.h>

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace dynslam::ekf
{
using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/** New state entries and their covariance with the existing state, to be appended. */
struct Augmentation
{
	Eigen::VectorXd mean;   ///< m new entries
	Eigen::MatrixXd cross;  ///< m x n: cov(new, existing), existing in state order
	Eigen::MatrixXd cov;    ///< m x m
};

/** Alg. 3: augment new point features from measurements z_k (in the model's measurement
 * space) taken at the ego pose x[0..2] by a sensor at `sensor` = (x, y, yaw) on the robot:
 *   mean_k = l(x (+) s, z_k), cross = L_x P[0:3, :], cov = L_x P_xx L_x^T + L_z R L_z^T
 * (blockwise), L_x = dl/dx through x (+) s (models::inverseObserveFromSensor).
 * @param P_ego_rows the first 3 rows of P (3 x n). */
Augmentation featureAugmentation(models::MeasurementModel model, const Eigen::Vector3d& ego,
                                 const Eigen::Ref<const RowMatrixXd>& P_ego_rows,
                                 const std::vector<Eigen::Vector2d>& z, const Eigen::Matrix2d& R,
                                 const Eigen::Vector3d& sensor = Eigen::Vector3d::Zero());

/** Alg. 4: augment the pose xi_t of one object from its features at time 0 and time t:
 *   mean = gamma(f0, ft), cross = Gamma1 P[f0, :] + Gamma2 P[ft, :],
 *   cov = Gamma P[f,f] Gamma^T + Gamma2 diag(Sigma_xi) Gamma2^T, Gamma = [Gamma1 Gamma2].
 * @param f0_idx state index of the x-coordinate of each time-0 feature (n entries).
 * @param ft_idx state index of the x-coordinate of each seen time-t feature (m entries).
 * @param seen seen[i] = which time-0 feature ft_idx[i] is (see models::objectPoseInverse).
 * For n == 1 the pose is translation-only (2 entries); otherwise it has 3 (dx, dy, dtheta).
 * @throws std::domain_error where gamma is undetermined (see objectPoseInverse). */
Augmentation objectPoseAugmentation(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const Eigen::Ref<const RowMatrixXd>& P,
                                    const std::vector<int>& f0_idx, const std::vector<int>& ft_idx,
                                    const std::vector<int>& seen, const Eigen::Matrix2d& Sigma_xi);

/** Alg. 4 linearized for one object: xi = gamma(f0, ft), its Jacobian Gamma = [Gamma1 Gamma2]
 * over the stacked state indices idx = [f0 ; ft] (two per feature), and noise = the fit
 * residual's covariance mapped to xi, sum_i Gamma2_i Sigma_xi Gamma2_i^T. Arguments and
 * exceptions as objectPoseAugmentation; x is only read at idx. */
struct ObjectPoseLinearization
{
	Eigen::VectorXd xi;
	Eigen::MatrixXd Gamma;
	std::vector<int> idx;
	Eigen::MatrixXd noise;
};
ObjectPoseLinearization linearizeObjectPose(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            const std::vector<int>& f0_idx,
                                            const std::vector<int>& ft_idx,
                                            const std::vector<int>& seen,
                                            const Eigen::Matrix2d& Sigma_xi, int centroidCols = 0);

/** Late joining (doc/results/classification.md): `pose` (a linearizeObjectPose result whose first
 * 2 * nc entries of idx are the object's founders' f0, nc = centroid columns) extended by the
 * time-0 positions of features that join the object at this step, f0_j = (g^o)^-1(xi, ft_j):
 *   3-dof: f0_j = R(dtheta)^T (ft_j - c0 - (dx, dy)) + c0, c0 the founders' centroid;
 *   2-dof (one founder): f0_j = ft_j - xi.
 * Entries of the result: xi (d), pads (mean 0, variance 1, uncorrelated) up to padTo >= d,
 * then 2 per joiner in order; idx gains each joiner's time-t feature (ft_idx: the x-entry);
 * noise gains the pose noise mapped to the joiners (they share it with xi).
 * @throws std::invalid_argument on inconsistent sizes. */
ObjectPoseLinearization appendJoinedFeatures(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const ObjectPoseLinearization& pose, int nc,
                                             const std::vector<int>& ft_idx, int padTo);

// --- Batched augmentation -----------------------------------------------------------------
// A step adds several groups of entries (new features, then object poses computed from them)
// and drops others. Resizing the covariance once per group costs a full copy each; these
// functions work on the state (x, P) "extended" by a pending Augmentation a, i.e. on
//   x_ext = [x; a.mean],  P_ext = [[P, a.cross^T], [a.cross, a.cov]],
// without forming P_ext, so that the owner resizes once per step.

/** Rows idx of P_ext (|idx| x (n + m)). */
Eigen::MatrixXd extendedRows(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                             const std::vector<int>& idx);

/** Alg. 4 for several objects at once, on the extended state: returns their poses as one
 * augmentation of the extended state (cross is size x (n + m)), pose o in the entries
 * at[o] .. at[o] + dim - 1 (at ascending, no overlap), every other entry a pad (mean 0,
 * variance 1, uncorrelated). Equal to augmenting the poses one after the other:
 * cov(xi_a, xi_b) = Gamma_a P_ext[idx_a, idx_b] Gamma_b^T. */
Augmentation objectPoseAugmentations(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                                     const std::vector<ObjectPoseLinearization>& poses,
                                     const std::vector<Eigen::Index>& at, Eigen::Index size);

/** The covariance of the state extended by a, then by b (b.cross has n + m_a columns; b may
 * have no entries), restricted to keep (ascending, in [0, n + m_a + m_b)), written to out,
 * which must have that size. */
void assembleExtended(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                      const Augmentation& b, const std::vector<int>& keep,
                      Eigen::Ref<RowMatrixXd> out);
/** assembleExtended in place: the n x n covariance is stored row-major at data with outer
 * stride `stride` (>= n and >= keep.size()); the kept old entries are moved towards the
 * top-left corner (nothing moves if nothing old is dropped) and the new ones written after
 * them, so the result is the keep.size() x keep.size() matrix at data with the same stride.
 * Bit-identical to assembleExtended (copies only). */
void assembleInPlace(double* data, Eigen::Index stride, Eigen::Index n, const Augmentation& a,
                     const Augmentation& b, const std::vector<int>& keep);

/** EKF update by a measurement that depends only on the entries idx of the state (Alg. 5 and
 * Alg. 6 are both of this form):
 *   S = H P[idx,idx] H^T + R, K = P[:,idx] H^T S^-1, x += K nu, P -= K S K^T.
 * H is m x |idx| (the Jacobian's non-zero columns), nu the innovation (m), R m x m.
 * Cost O(n^2 m + n m^2) instead of the dense O(n^3): with W = P[:,idx] H^T L^-T (S = L L^T),
 * P -= W W^T as a symmetric rank-m update of one triangle, mirrored to the other, so P stays
 * exactly symmetric.
 * @return the NIS nu^T S^-1 nu.
 * @throws std::runtime_error if S is not positive definite. */
double sparseUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                    const std::vector<int>& idx, const Eigen::MatrixXd& H,
                    const Eigen::VectorXd& nu, const Eigen::MatrixXd& R);

/** Alg. 6 for one object: smoothing pseudo-measurement 0 = s(xi_{t-2}, xi_{t-1}, xi_t) + n_s,
 * n_s ~ N(0, Sigma_s), applied by sparseUpdate. Each *_idx is the index of the pose's first
 * entry; the pose occupies d consecutive entries (d = 2 or 3, Sigma_s is d x d).
 * @return the NIS. */
double smoothingUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, int xi_tm2_idx,
                       int xi_tm1_idx, int xi_t_idx, const Eigen::MatrixXd& Sigma_s);

/** A pseudo-measurement 0 = r(poses) + n, n ~ N(0, R), on poses of d entries each whose
 * first entries are at `base` (an object motion model, dynslam/estimator/object_motion_model.h;
 * Alg. 6 is one): residual(values, &J) returns r and J_r_pose per pose. Applied by
 * sparseUpdate with nu = -r; angles (entry 2 of 3-dof poses) wrapped afterwards.
 * @return the NIS. */
using PoseResidualFn = std::function<Eigen::VectorXd(const std::vector<Eigen::VectorXd>&,
                                                     std::vector<Eigen::MatrixXd>*)>;
double pseudoMeasurementUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                               const std::vector<int>& base, int d, const PoseResidualFn& residual,
                               const Eigen::MatrixXd& R);
/** Alg. 7: propagate the ego pose x[0..2] by the odometry increment u (x <- x (+) u) with
 * noise Sigma_u on the increment: P_xx <- F P_xx F^T + G Sigma_u G^T, P_xe <- F P_xe.
 * fej_previous_prediction (first-estimate Jacobians, Huang et al. 2008): if given, the heading
 * column of F uses the ego position difference of the predicted estimates,
 * p_{k+1|k} - p_{k|k-1} with p_{k|k-1} = *fej_previous_prediction, instead of R(theta) u. The
 * product's Alg. 7 (CDynamicKFSLAM2D) is this function. J_out_x_used: the F that was used. */
void propagate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, const Eigen::Vector3d& u,
               const Eigen::Matrix3d& Sigma_u,
               const Eigen::Vector3d* fej_previous_prediction = nullptr,
               Eigen::Matrix3d* J_out_x_used = nullptr);

/** Prediction of the entries idx of the state by a transition whose Jacobian is F
 * (|idx| x |idx|) and process noise Q (object motion models, models/object_motion.h):
 *   x[idx] = x_new, P[idx,:] <- F P[idx,:], P[:,idx] <- P[:,idx] F^T, P[idx,idx] += Q.
 * O(n |idx|^2); the other entries are unchanged. Entries outside idx keep their exact
 * values; P stays exactly symmetric. */
void predictSubset(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                   const std::vector<int>& idx, const Eigen::VectorXd& x_new,
                   const Eigen::MatrixXd& F, const Eigen::MatrixXd& Q);
/** The indices 0..n-1 that are not in `remove` (any order, duplicates allowed), ascending. */
std::vector<int> keptIndices(int n, const std::vector<int>& remove);

/** Marginal covariance P[idx, idx]. */
Eigen::MatrixXd marginal(const Eigen::Ref<const RowMatrixXd>& P, const std::vector<int>& idx);
}  // namespace dynslam::ekf
