#pragma once
/** @file classify_evidence.h
 * The statistics of the classifying router (doc/results/classification.md), pure functions:
 * a reading as a point in the robot frame, a static point carried through the odometry
 * increment, the log-likelihood ratio of one reading (moving vs static), the chi-square
 * quantile, and the rigid-distance test of two tracks. */
#include <dynslam/estimator/measurement_router.h>

#include <Eigen/Core>
#include <map>

namespace dynslam::estimator
{
/** A point in the robot frame with its covariance. */
struct TPoint2
{
	Eigen::Vector2d p = Eigen::Vector2d::Zero();
	Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
};

/** Reading z (model space) as a point in the robot frame, covariance J_q_z R J_q_z^T. */
TPoint2 readingInRobotFrame(const TRouterContext& ctx, const Eigen::Vector2d& z);

/** A static point q of the previous robot frame seen from the robot after the increment u:
 * q' = R(u_th)^T (q - u_xy), covariance J_q C J_q^T + J_u U J_u^T. */
TPoint2 predictStatic(const TPoint2& q, const Eigen::Vector3d& u, const Eigen::Matrix3d& U);

/** One odometry increment with its rotations computed once, for carrying many points through it
 * (the same arithmetic as predictStatic(q, u, U): bit-identical results). */
struct TStaticMotion
{
	TStaticMotion(const Eigen::Vector3d& u_, const Eigen::Matrix3d& U_);
	Eigen::Vector3d u;
	Eigen::Matrix3d U;
	Eigen::Matrix2d Rt;   ///< R(u_th)^T
	Eigen::Matrix2d dRt;  ///< (dR/dth (u_th))^T
};
TPoint2 predictStatic(const TPoint2& q, const TStaticMotion& m);

/** The log-likelihood ratio of innovation nu: log N(nu; 0, S + Q) - log N(nu; 0, S), S the
 * innovation covariance of the static hypothesis, Q the extra spread of the moving one. */
double movingLogLikelihoodRatio(const Eigen::Vector2d& nu, const Eigen::Matrix2d& S,
                                const Eigen::Matrix2d& Q);

/** Quantile of the chi-square distribution with `dof` >= 1 degrees of freedom at probability
 * p in (0, 1): exact for 2 dof, Wilson-Hilferty otherwise (within 1 % for p in [0.9, 0.999]). */
double chiSquareQuantile(double p, int dof);

/** Rigid-distance test of two tracks over their common steps (a: step -> point): the
 * distances d_t = |a_t - b_t|, their variances g^T (C_a + C_b) g (g the unit direction), the
 * weighted mean and chi2 = sum (d_t - mean)^2 / var_t with n - 1 dof. */
struct TRigidTest
{
	int common = 0;        ///< common steps n
	double chi2 = 0;       ///< (n - 1) dof
	double mean_dist = 0;  ///< weighted mean distance [m]
};
TRigidTest rigidDistanceTest(const std::map<int, TPoint2>& a, const std::map<int, TPoint2>& b);

/** Is the distance of two points now (za, zb) the one their tracks kept before (a, b: step ->
 * point, without the current step)? The weighted mean of the earlier distances (as
 * rigidDistanceTest) against d_now: z2 = (d_now - mean)^2 / (var_now + 1 / sum w), 1 dof;
 * past = the number of earlier common steps (0: untestable, z2 = 0). */
struct TRigidNow
{
	int past = 0;
	double z2 = 0;
};
TRigidNow rigidNowTest(const std::map<int, TPoint2>& a, const TPoint2& za,
                       const std::map<int, TPoint2>& b, const TPoint2& zb);

}  // namespace dynslam::estimator
