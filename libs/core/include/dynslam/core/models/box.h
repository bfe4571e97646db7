#pragma once
/** @file box.h
 * Measurement model of an oriented box in the ego frame (issue 31, item 1; pure Eigen): what a
 * 3-D detector gives in the bird's-eye view, for a moving object or a static box (a parked car
 * as a landmark).
 *
 * State blocks: the ego pose x = (p_x, p_y, theta) and the object's pose o = (o_x, o_y, psi)
 * in the world (centre of the footprint, heading of its length axis), and its extent
 * e = (length, width). The measurement z = (c_x, c_y, phi, length, width):
 *
 *     c   = R(theta)^T (o_xy - p)     the centre in the ego frame
 *     phi = wrap(psi - theta)         the heading in the ego frame, in (-pi, pi]
 *     (length, width) = e
 *
 * A detector cannot tell a box's front from its back: a measured heading phi and phi + pi
 * describe the same box. The model keeps the heading on the full circle (so an object's
 * heading and its motion agree) and resolves the ambiguity in the innovation (boxInnovation):
 * the heading residual is taken modulo pi, in (-pi/2, pi/2]. The Jacobians are those of h; the
 * flip by pi is a constant and does not change them. */
#include <Eigen/Core>

namespace dynslam::models
{
using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix53d = Eigen::Matrix<double, 5, 3>;
using Matrix52d = Eigen::Matrix<double, 5, 2>;

/** z = h(x, o, e). J_z_x: d z / d x (5x3), J_z_o: d z / d o (5x3), J_z_e: d z / d e (5x2). */
Vector5d boxObserve(const Eigen::Vector3d& x, const Eigen::Vector3d& o, const Eigen::Vector2d& e,
                    Matrix53d* J_z_x = nullptr, Matrix53d* J_z_o = nullptr,
                    Matrix52d* J_z_e = nullptr);

/** The inverse for the object's pose: o = (p + R(theta) c, wrap(theta + phi)); e = (z_3, z_4)
 * directly. J_o_x: d o / d x (3x3), J_o_z: d o / d z (3x5). */
Eigen::Vector3d boxInverse(const Eigen::Vector3d& x, const Vector5d& z,
                           Eigen::Matrix3d* J_o_x = nullptr,
                           Eigen::Matrix<double, 3, 5>* J_o_z = nullptr);

/** Innovation z - zhat with the heading residual modulo pi in (-pi/2, pi/2] (front/back
 * ambiguity); *flipped (optional) says whether pi was taken off, i.e. the detector's heading
 * points to the box's back. */
Vector5d boxInnovation(const Vector5d& z, const Vector5d& zhat, bool* flipped = nullptr);
}  // namespace dynslam::models
