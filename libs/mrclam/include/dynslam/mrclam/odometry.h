#pragma once
/** @file odometry.h
 * Odometry of the MRCLAM robots (velocity commands v, w at about 67 Hz) integrated exactly
 * into SE(2) increments, the odometry noise model, and ground-truth interpolation.
 * Pure Eigen (no MRPT).
 *
 * Integration (zero-order hold with a delay d): the command (v_i, w_i) logged at t_i acts on
 * [t_i + d, t_{i+1} + d); before the first row the robot stands still; the last row holds
 * until the end. d models the actuation/logging latency (about 0.2 s on Dataset 6, estimated
 * from the ground truth, see noise_estimation.h). Optional gains scale the commands:
 * (v, w) -> (scale_v v, scale_w w) (a calibration, also estimated from the ground truth). Each
 * piece is a unicycle arc, integrated exactly: w != 0: dx = v/w sin(w dt), dy = v/w (1 - cos(w
 * dt)), dtheta = w dt w == 0: dx = v dt,          dy = 0,                   dtheta = 0 and the
 * pieces are composed in SE(2). The increment from t_a to t_b is expressed in the robot frame at
 * t_a (MRPT's CActionRobotMovement2D convention: x_b = x_a (+) increment). */
#include <dynslam/mrclam/mrclam_files.h>

#include <Eigen/Core>
#include <vector>

namespace dynslam::mrclam
{
/** One integrated odometry increment. */
struct TOdometryIncrement
{
	Eigen::Vector3d delta = Eigen::Vector3d::Zero();  ///< (dx, dy, dtheta) in the frame at t_a
	double distance = 0;                              ///< integrated path length  sum |v| dt  [m]
	double angle = 0;  ///< integrated absolute rotation  sum |w| dt  [rad]
};

/** The exact arc of a unicycle with constant (v, w) during dt. */
Eigen::Vector3d unicycleArc(double v, double w, double dt);
/** SE(2) composition a (+) b, angle wrapped to (-pi, pi]. */
Eigen::Vector3d composeSE2(const Eigen::Vector3d& a, const Eigen::Vector3d& b);
/** SE(2) inverse composition b (-) a = a^-1 (+) b, angle wrapped. */
Eigen::Vector3d relativeSE2(const Eigen::Vector3d& a, const Eigen::Vector3d& b);
double wrapAngle(double a);

class COdometryIntegrator
{
public:
	/** rows must be sorted by time (readOdometry guarantees it); delay d [s] and gains as
	 * above. */
	explicit COdometryIntegrator(std::vector<TOdometryRow> rows, double delay = 0,
	                             double scaleV = 1, double scaleW = 1);
	/** Increment from ta to tb (ta <= tb, else std::invalid_argument). */
	TOdometryIncrement integrate(double ta, double tb) const;

private:
	std::vector<TOdometryRow> m_rows;
};

/** Gaussian odometry noise on the increment (additive in the frame at t_a):
 *   var_xy  = std_xy_min^2  + var_xy_per_m  * distance + var_xy_per_rad  * angle  (x and y)
 *   var_phi = std_phi_min^2 + var_phi_per_m * distance + var_phi_per_rad * angle
 * i.e. a random walk whose variance grows linearly with the integrated path length and the
 * integrated absolute rotation, plus a floor. Covariance = diag(var_xy, var_xy, var_phi).
 *
 * Correlated errors (model = inflated): real odometry errors are correlated over many steps,
 * so the variance of a sum of N increment errors is N var tau (tau = the integrated
 * autocorrelation time of the normalized errors, in steps, noise_estimation.h) rather than
 * N var. The inflated model multiplies var_xy by tau_xy and var_phi by tau_phi: still white per
 * step (what an EKF can use), but with the long-horizon variance of the correlated errors. */
struct TOdometryNoiseModel
{
	enum class Model
	{
		white,    ///< the fit as it is (independent steps)
		inflated  ///< var_xy * tau_xy, var_phi * tau_phi
	};
	double std_xy_min = 1e-3;       ///< [m]
	double var_xy_per_m = 1e-4;     ///< [m^2/m]
	double var_xy_per_rad = 0;      ///< [m^2/rad]
	double std_phi_min = 1e-3;      ///< [rad]
	double var_phi_per_m = 1e-3;    ///< [rad^2/m]
	double var_phi_per_rad = 1e-3;  ///< [rad^2/rad]
	Model model = Model::white;
	double tau_xy = 1;   ///< [steps] >= 1, used by Model::inflated
	double tau_phi = 1;  ///< [steps] >= 1, used by Model::inflated
	Eigen::Matrix3d covariance(const TOdometryIncrement& inc) const;
};

/** Linear interpolation of a Vicon trajectory, the angle along the shorter arc (wrapped). */
class CTrajectoryInterpolator
{
public:
	explicit CTrajectoryInterpolator(std::vector<TPoseRow> rows);  ///< sorted, >= 2 rows
	double tBegin() const { return m_rows.front().t; }
	double tEnd() const { return m_rows.back().t; }
	bool covers(double t) const { return t >= tBegin() && t <= tEnd(); }
	/** Pose at t; throws std::out_of_range outside [tBegin, tEnd]. */
	Eigen::Vector3d at(double t) const;
	/** Largest time gap between consecutive rows within [ta, tb]. */
	double maxGap(double ta, double tb) const;

private:
	std::vector<TPoseRow> m_rows;
};
}  // namespace dynslam::mrclam
