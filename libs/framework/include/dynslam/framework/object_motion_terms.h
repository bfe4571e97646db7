#pragma once
/** @file object_motion_terms.h
 * The terms of the object-centric motion models (issue 13, `object_model = cv | ctrv`;
 * doc/framework.md "Object-centric motion models"):
 *
 * | term                    | residual                                         | information     |
 * |-------------------------|--------------------------------------------------|-----------------|
 * | CObjectMotionTerm       | [xi_t; v_t] (-) f([xi_{t-1}; v_{t-1}])            | (a Q)^-1        |
 * | CObjectMixtureMotionTerm | [xi_t; v_t] (-) (s_bar + F_bar ds) (mm)          | Q_eff^-1        |
 * | CObjectSightingTerm     | z - h(x_t (+) s, g(xi_t, f_0)_k) (bearing wrapped) | Sigma_v^-1     |
 * | CObjectVelocityInitTerm | v - v0(xi) (the model's initial velocity)          | Sigma_v0^-1    |
 *
 * f, Q and v0 are the IObjectMotionModel's (predict, initialVelocity): the same functions the
 * EKF uses. A marginalization of (xi_{t-1}, v_{t-1}) with the motion term is the EKF's object
 * prediction; a GN step on the sighting terms of an object is its measurement update; a GN step
 * on the initialisation term is the EKF's velocity augmentation. */
#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/framework/terms.h>

namespace dynslam::framework
{
/** Keys {xi_{t-1}, v_{t-1}, xi_t, v_t}; throws std::invalid_argument if the process noise Q is
 * not positive definite (a zero spectral density: the framework needs an invertible one). */
class CObjectMotionTerm : public CTerm
{
public:
	CObjectMotionTerm(std::shared_ptr<const estimator::IObjectMotionModel> model,
	                  const TVarKey& xiPrev, const TVarKey& vPrev, const TVarKey& xi,
	                  const TVarKey& v);
	std::string name() const override { return "object_motion:" + m_model->name(); }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	std::shared_ptr<const estimator::IObjectMotionModel> m_model;
};

/** object_model = mm (issue 28): the moment-matched mixture of the modes' motion
 * (models/mode_mixture.h, estimator::CObjectModes) as a term linear about the estimate s_lin of
 * [xi_{t-1}; v_{t-1}] at which the mixture was made: residual [xi_t; v_t] (-) (s_bar + F_bar
 * (s_{t-1} (-) s_lin)), information Q_eff^-1. It is marginalized as soon as it is added (the
 * prediction), so it is linearized at s_lin only: the EKF's mixed prediction. Keys as
 * CObjectMotionTerm; throws std::invalid_argument if Q_eff is not positive definite. */
class CObjectMixtureMotionTerm : public CTerm
{
public:
	CObjectMixtureMotionTerm(const TVarKey& xiPrev, const TVarKey& vPrev, const TVarKey& xi,
	                         const TVarKey& v, const Eigen::VectorXd& s_lin,
	                         const models::TModeMixture& mix);
	std::string name() const override { return "object_motion:mm"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	Eigen::VectorXd m_sLin;
	models::TModeMixture m_mix;
	Eigen::MatrixXd m_info;
};

/** A sighting of feature k of an object with pose xi_t and time-0 (body-frame) features f0
 * (all n of them: the centroid of the pose map depends on all). Keys {x_t, xi_t, f0...}. */
class CObjectSightingTerm : public CTerm
{
public:
	CObjectSightingTerm(int t, const TVarKey& xi, const std::vector<TVarKey>& f0, int k,
	                    const Eigen::Vector2d& z, models::MeasurementModel model,
	                    const Eigen::Matrix2d& Sigma_v,
	                    const Eigen::Vector3d& sensor = Eigen::Vector3d::Zero());
	std::string name() const override { return "object_sighting"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	int m_k;
	Eigen::Vector2d m_z;
	Eigen::Vector3d m_sensor;
	models::MeasurementModel m_model;
	Eigen::Matrix2d m_info;
};

/** The velocity of a new object from its first pose, `steps` steps after its first sighting:
 * v = v0(xi) + n, n ~ N(0, Sigma_v0) (IObjectMotionModel::initialVelocity). Keys {xi, v}. */
class CObjectVelocityInitTerm : public CTerm
{
public:
	CObjectVelocityInitTerm(std::shared_ptr<const estimator::IObjectMotionModel> model,
	                        const TVarKey& xi, const TVarKey& v, int steps, int poseDim);
	std::string name() const override { return "object_velocity_init"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	std::shared_ptr<const estimator::IObjectMotionModel> m_model;
	int m_steps;
	Eigen::MatrixXd m_info;
};
}  // namespace dynslam::framework
