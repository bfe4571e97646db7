#pragma once
/** @file constant_velocity.h
 * The constant-velocity object motion model (issue 13, `object_model = cv`): an object's
 * state is its pose and its world-frame velocity (models/object_motion.h), predicted every
 * step; its sightings update ego, pose and body-frame features together. Objects help the
 * ego: a car driving steadily beside it is a reference where static landmarks are scarce. */
#include <dynslam/estimator/object_motion_model.h>

#include <map>

namespace dynslam::estimator
{
struct TCvParams
{
	double dt = 0.5;  ///< seconds per step [s]
	/** White-acceleration spectral densities (ax, ay, alpha) [m^2/s^3, m^2/s^3, rad^2/s^3]. */
	Eigen::Vector3d accel_psd = Eigen::Vector3d(0.1, 0.1, 0.01);
	/** Std of the initialisation noise of the velocity (vx, vy, omega) [m/s, m/s, rad/s]. */
	Eigen::Vector3d velocity_prior_std = Eigen::Vector3d(1.0, 1.0, 0.1);
	/** ca only (constant_acceleration.h; validated by CConstantAcceleration): white-jerk
	 * spectral densities (jx, jy, jalpha) [m^2/s^5, m^2/s^5, rad^2/s^5] and the std of the
	 * acceleration prior (ax, ay, alpha) [m/s^2, m/s^2, rad/s^2]. */
	Eigen::Vector3d jerk_psd = Eigen::Vector3d(0.01, 0.01, 0.001);
	Eigen::Vector3d accel_prior_std = Eigen::Vector3d(0.5, 0.5, 0.05);
	/** mm only (multiple_model.h; validated by CMultipleModel): the probability of leaving a
	 * mode per step, in (0, 1), and the manoeuvre mode's white-acceleration spectral densities
	 * [m^2/s^3, m^2/s^3, rad^2/s^3] (> 0). */
	double mm_switch_prob = 0.01;
	Eigen::Vector3d mm_manoeuvre_psd = Eigen::Vector3d(16.0, 16.0, 0.1);
	/** Chi-square threshold (2 dof) of the gate on object readings (infinity: no gate). */
	double gate = std::numeric_limits<double>::infinity();
	/** Fallback of a lost object (doc/state-layout.md "Fallback of a lost object"): after
	 * fallback_steps consecutive steps whose readings of an object were all gated out, the
	 * object's velocity and pose leave the state; it is then handled by the paper's
	 * formulation (Alg. 3, 4) until two of its poses give a new velocity. 0 = off (default). */
	int fallback_steps = 0;
	/** Heading inflation c (doc/state-layout.md "Heading inflation of object readings"): each
	 * object reading used in an update gets the noise Sigma_v + c P_thth h h^T, h its Jacobian
	 * column on the ego heading and P_thth the ego heading variance before the object update:
	 * an object's information on the ego shrinks when the ego heading is poorly known (at the
	 * Table I levels with large odometry noise that variance is mostly the unobservable prior
	 * heading, which the object readings otherwise leak into the estimate; doc/results/results.md
	 * 4.3.2). The gate is unchanged. 0 = off (default). EKF only. */
	double heading_inflation = 0.0;
	/** Throws std::invalid_argument naming the parameter. */
	void validate() const;
};

class CConstantVelocity : public IObjectMotionModel
{
public:
	explicit CConstantVelocity(const TCvParams& p);
	std::string name() const override { return "cv"; }
	int posesNeeded() const override { return 1; }
	std::vector<TPseudoMeasurement> select(int32_t, int, const std::vector<int>&,
	                                       int) const override
	{
		return {};
	}
	Eigen::VectorXd residual(const TPseudoMeasurement&, const std::vector<Eigen::VectorXd>&,
	                         std::vector<Eigen::MatrixXd>*) const override;
	int velocityDim(int poseDim) const override { return poseDim; }
	Eigen::VectorXd predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
	                        Eigen::MatrixXd* Q) const override;
	Eigen::VectorXd initialVelocity(const Eigen::VectorXd& xi, int steps, Eigen::MatrixXd* J_v_xi,
	                                Eigen::MatrixXd* Sigma) const override;
	double readingGate() const override { return m_p.gate; }
	const TCvParams& params() const { return m_p; }
	bool reportGating(int32_t object, bool allGatedOut) override;
	void resetObjectState() override
	{
		m_gatedSteps.clear();
		m_fallbacks = 0;
	}
	/** Objects handed back to the paper's formulation since construction/reset. */
	size_t fallbackCount() const { return m_fallbacks; }

private:
	TCvParams m_p;
	std::map<int32_t, int> m_gatedSteps;  ///< consecutive all-gated-out steps per object
	size_t m_fallbacks = 0;
};
}  // namespace dynslam::estimator
