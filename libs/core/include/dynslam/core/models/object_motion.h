#pragma once
/** @file object_motion.h
 * Object-centric motion models (issue 13): an object's state is its pose xi (the pose map of
 * models/object_pose.h: the motion since its first sighting, a rotation about the time-0
 * centroid c0 followed by a translation) and its velocity; its features are kept in the
 * object's body frame, which is the world frame at the object's first sighting (f_0).
 *
 * Constant velocity (CV), world frame: s = [xi; v] with v = (vx, vy, omega) the world-frame
 * velocity of the reference point c0 + (dx, dy) and the turn rate (for a translation-only pose,
 * d = 2: v = (vx, vy)). One step of dt seconds:
 *
 *     xi' = xi + dt v   (dtheta wrapped to (-pi, pi]),   v' = v   (+ process noise)
 *
 * The model is linear; the only nonlinearity is the angle wrap. The process noise is white
 * acceleration with spectral density q_i per axis (discrete form, per axis i):
 *     Q_i = q_i [dt^3/3  dt^2/2; dt^2/2  dt]   on (xi_i, v_i).
 *
 * Constant turn rate and velocity (CTRV), the same state: the reference point moves with a
 * constant speed and a velocity that turns at omega (a rigid body with a constant body-frame
 * twist: every point of it moves on a circle at the same omega). With a = omega dt,
 *
 *     p'  = p + A(omega) v,   A = [S -C; C S],  S = sin(a)/omega,  C = (1 - cos a)/omega
 *     th' = th + a (wrapped),  v' = R(a) v,  omega' = omega   (+ process noise)
 *
 * For |a| < 1e-2 S and C (and their derivatives) are evaluated by their Taylor series (no
 * division by omega; omega = 0 gives exactly the CV step). Zero speed needs no special case
 * (nothing divides by |v|). A translation-only pose (d = 2) has no turn rate: CTRV is then CV.
 *
 * A sighting of feature k of an object is z = h(x_ego, g(xi, f0)_k): the measurement of
 * ego, object pose and the object's body-frame features together. */
#include <dynslam/core/models/measurement.h>

#include <Eigen/Core>

namespace dynslam::models
{
/** CV prediction of s = [xi; v] (2d entries, d = 2 or 3) over dt: returns s'; J_out_s
 * (2d x 2d) = [I, dt I; 0, I]. Throws std::invalid_argument on a wrong size. */
Eigen::VectorXd cvPredict(const Eigen::VectorXd& s, double dt, Eigen::MatrixXd* J_out_s = nullptr);

/** CTRV prediction of s = [xi; v] (6 entries; 4 entries: the CV step) over dt: returns s';
 * J_out_s (6 x 6) the exact Jacobian (series near omega = 0). Throws std::invalid_argument on
 * a wrong size. */
Eigen::VectorXd ctrvPredict(const Eigen::VectorXd& s, double dt,
                            Eigen::MatrixXd* J_out_s = nullptr);

/** White-acceleration process noise of the CV model for d = q.size() axes (2d x 2d, entries
 * ordered as s = [xi; v]). q >= 0. */
Eigen::MatrixXd cvProcessNoise(const Eigen::VectorXd& q, double dt);

/** Velocity of an object from its first pose xi, `elapsed` seconds after its time 0 (whose pose
 * is the identity): v = xi / elapsed, J_v_xi = I / elapsed. elapsed > 0. */
Eigen::VectorXd cvInitialVelocity(const Eigen::VectorXd& xi, double elapsed,
                                  Eigen::MatrixXd* J_v_xi = nullptr);

/** Position of feature k of an object with pose xi (2 or 3 entries) and body-frame (time-0)
 * features f0 (2 x n): g(xi, f0)_k, with J_f_xi (2 x d) and J_f_f0 (2 x 2n). For d = 2:
 * f0_k + xi. centroidCols: c0 is the centroid of the first centroidCols columns (0: all; an
 * object's founders, after a merge, models/object_merge.h). */
Eigen::Vector2d objectFeatureAt(const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0, int k,
                                Eigen::MatrixXd* J_f_xi = nullptr,
                                Eigen::MatrixXd* J_f_f0 = nullptr, int centroidCols = 0);

/** Sighting of feature k of an object: z = h(x, g(xi, f0)_k) in model m's space, with J_z_x
 * (2x3), J_z_xi (2 x d), J_z_f0 (2 x 2n). */
Eigen::Vector2d observeObjectFeature(MeasurementModel m, const Eigen::Vector3d& x,
                                     const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0, int k,
                                     Matrix23d* J_z_x = nullptr, Eigen::MatrixXd* J_z_xi = nullptr,
                                     Eigen::MatrixXd* J_z_f0 = nullptr, int centroidCols = 0);

/** The same from a sensor at pose s on the robot: z = h(x (+) s, g(xi, f0)_k)
 * (models::observeFromSensor). */
Eigen::Vector2d observeObjectFeatureFromSensor(
    MeasurementModel m, const Eigen::Vector3d& x, const Eigen::Vector3d& s,
    const Eigen::VectorXd& xi, const Eigen::Matrix2Xd& f0, int k, Matrix23d* J_z_x = nullptr,
    Eigen::MatrixXd* J_z_xi = nullptr, Eigen::MatrixXd* J_z_f0 = nullptr, int centroidCols = 0);
}  // namespace dynslam::models
