#pragma once
/** @file terms.h
 * Residual terms of the running cost (paper Section II). A term touches a list of variable
 * blocks (keys) and contributes r(x)^T W r(x) to the cost, with r its residual and W its
 * information (inverse covariance, PSD). linearize() gives r, W and dr/dx_i per block at the
 * given values (the linearization point x*).
 *
 * Every model comes from dynslam::models (libs/core): h/l and their Jacobians from
 * measurement.h, g^o and gamma from object_pose.h, s from smoothing.h, odometry from se2.h.
 *
 * | term                    | residual                               | information            |
 * |-------------------------|----------------------------------------|------------------------|
 * | CPriorTerm              | x (-) mu (blocks stacked)              | Omega (PSD)            |
 * | COdometryTerm           | x_{t+1} (-) (x_t (+) u)                | (G Sigma_u G^T)^-1     |
 * | CMeasurementTerm        | z - h(x_t (+) s, f)  (bearing wrapped) | Sigma_v^-1            |
 * | CObjectPoseFeatureTerm  | f_t - g^o(xi_t, f_0)  (paper, 2m rows) | diag(Sigma_xi^-1)      |
 * | CObjectPosePoseTerm     | xi_t (-) gamma(f_0, f_t)  (d rows)     | (Gamma2 diag(Sigma_xi)
 * Gamma2^T)^-1 | | CSmoothingTerm          | s(xi_{t-2}, xi_{t-1}, xi_t)            | Sigma_s^-1 |
 * | CMotionModelTerm        | r of an object motion model's pseudo-measurement | R^-1         |
 * | CBodyPoseMeasurementTerm| (x_t^-1 (+) O_t) (-) T  (CubeSLAM-like) | Sigma_T^-1            |
 *
 * State-dependent informations (odometry, pose-space object pose) are evaluated at the
 * linearization point (as the EKF does with its Jacobians). */
#include <dynslam/core/models/measurement.h>
#include <dynslam/estimator/object_motion_model.h>
#include <dynslam/framework/variables.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace dynslam::framework
{
/** r, W and the Jacobians dr/dx_i (one per key, in key order) at a linearization point. */
struct TLinearization
{
	Eigen::VectorXd r;
	Eigen::MatrixXd W;
	std::vector<Eigen::MatrixXd> J;
};

/** Base class of the residual terms. */
class CTerm
{
public:
	explicit CTerm(std::vector<TVarKey> keys) : m_keys(std::move(keys)) {}
	virtual ~CTerm() = default;
	virtual std::string name() const = 0;
	const std::vector<TVarKey>& keys() const { return m_keys; }
	bool touches(const TVarKey& k) const;
	/** @param x the current values of keys() (same order). */
	virtual TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const = 0;

protected:
	std::vector<TVarKey> m_keys;
};
using CTermPtr = std::shared_ptr<const CTerm>;

/** Gaussian prior ||x (-) mu||^2_Omega on a set of blocks: what a GN step (Alg. 1: "cost <-
 * ||x - mu||^2_{Sigma^-1}") or a marginalization leaves. Omega may be singular (PSD). */
class CPriorTerm : public CTerm
{
public:
	/** @param dims block sizes; mean stacked in key order; information PSD. */
	CPriorTerm(std::vector<TVarKey> keys, std::vector<int> dims, Eigen::VectorXd mean,
	           Eigen::MatrixXd information);
	/** From a covariance (must be positive definite; throws std::invalid_argument otherwise). */
	static std::shared_ptr<CPriorTerm> fromCovariance(std::vector<TVarKey> keys,
	                                                  std::vector<int> dims, Eigen::VectorXd mean,
	                                                  const Eigen::MatrixXd& covariance);
	std::string name() const override { return "prior"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;
	const Eigen::VectorXd& mean() const { return m_mean; }
	const Eigen::MatrixXd& information() const { return m_info; }
	const std::vector<int>& dims() const { return m_dims; }

private:
	std::vector<int> m_dims;
	Eigen::VectorXd m_mean;
	Eigen::MatrixXd m_info;
};

/** Ego motion x_{t+1} = x_t (+) u + w, noise Sigma_u on the robot-frame increment
 * (models::composePose). */
class COdometryTerm : public CTerm
{
public:
	COdometryTerm(int t_from, int t_to, const Eigen::Vector3d& u, const Eigen::Matrix3d& Sigma_u);
	std::string name() const override { return "odometry"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	Eigen::Vector3d m_u;
	Eigen::Matrix3d m_Sigma_u;
};

/** Point measurement z = h(x_t, f) + v, v ~ N(0, Sigma_v), either measurement model. The
 * feature is a static landmark or an object feature (any 2-dof block). */
class CMeasurementTerm : public CTerm
{
public:
	/** sensor: the sensor's pose (x, y, yaw) on the robot; z = h(x_t (+) sensor, f). */
	CMeasurementTerm(int t, const TVarKey& feature, const Eigen::Vector2d& z,
	                 models::MeasurementModel model, const Eigen::Matrix2d& Sigma_v,
	                 const Eigen::Vector3d& sensor = Eigen::Vector3d::Zero());
	std::string name() const override { return "measurement"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	Eigen::Vector2d m_z;
	Eigen::Vector3d m_sensor;
	models::MeasurementModel m_model;
	Eigen::Matrix2d m_info;
};

/** Keys of one object-pose residual: xi_t, its n time-0 features and m seen time-t features. */
struct TObjectPoseKeys
{
	TVarKey pose;             ///< ObjectPose, dim 3 (or 2 if n == 1)
	std::vector<TVarKey> f0;  ///< all n time-0 features
	std::vector<TVarKey> ft;  ///< the m features seen at time t
	std::vector<int> seen;    ///< seen[i] = index into f0 of ft[i]
};

/** The paper's object-pose residual in feature space (Section II step 2, Theorem 4.1):
 * f_t,k - g^o(xi_t, f_0)_k for every seen k, each with Sigma_xi (2m rows). For n = 1
 * (translation-only pose), g^o(xi, f_0) = f_0 + xi. */
class CObjectPoseFeatureTerm : public CTerm
{
public:
	CObjectPoseFeatureTerm(const TObjectPoseKeys& k, const Eigen::Matrix2d& Sigma_xi);
	std::string name() const override { return "object_pose_feature_space"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	size_t m_n, m_m;
	std::vector<int> m_seen;
	Eigen::Matrix2d m_info;
};

/** The object-pose residual in pose space, xi_t (-) gamma(f_0, f_t), with covariance
 * Gamma2 diag(Sigma_xi) Gamma2^T (Gamma2 = d gamma / d f_t at the linearization point). A GN
 * step on it is exactly Alg. 4 (see doc/framework.md). */
class CObjectPosePoseTerm : public CTerm
{
public:
	CObjectPosePoseTerm(const TObjectPoseKeys& k, const Eigen::Matrix2d& Sigma_xi);
	std::string name() const override { return "object_pose_pose_space"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	size_t m_n, m_m;
	std::vector<int> m_seen;
	Eigen::Matrix2d m_Sigma_xi;
};

/** Smoothing residual s(xi_{t-2}, xi_{t-1}, xi_t) with Sigma_s (models::smoothingResidual). */
class CSmoothingTerm : public CTerm
{
public:
	CSmoothingTerm(const TVarKey& xi_tm2, const TVarKey& xi_tm1, const TVarKey& xi_t,
	               const Eigen::MatrixXd& Sigma_s);
	std::string name() const override { return "smoothing"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	Eigen::MatrixXd m_info;
};

/** A pseudo-measurement 0 = r(poses) + n of an object motion model
 * (dynslam/estimator/object_motion_model.h) on the object poses it names: the same object the
 * EKF applies as an update (ekf::pseudoMeasurementUpdate). */
class CMotionModelTerm : public CTerm
{
public:
	CMotionModelTerm(std::shared_ptr<const estimator::IObjectMotionModel> model,
	                 const estimator::TPseudoMeasurement& m);
	std::string name() const override { return "motion_model:" + m_model->name(); }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	std::shared_ptr<const estimator::IObjectMotionModel> m_model;
	estimator::TPseudoMeasurement m_meas;
	Eigen::MatrixXd m_info;
};

/** CubeSLAM-like object measurement: the pose T of the object's body frame in the sensor
 * frame (a pose fit of its features), T = x_t^-1 (+) O_t + n, n ~ N(0, Sigma_T). O_t is an
 * ObjectBodyPose (global, 3-dof; 2-dof position for one-feature objects, then T is a point).
 * The translation part is models::cartesianObserve(x_t, position of O_t). */
class CBodyPoseMeasurementTerm : public CTerm
{
public:
	CBodyPoseMeasurementTerm(int t, const TVarKey& body, const Eigen::VectorXd& T,
	                         const Eigen::MatrixXd& Sigma_T);
	std::string name() const override { return "body_pose_measurement"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override;

private:
	Eigen::VectorXd m_T;
	Eigen::MatrixXd m_info;
};

/** Inverse of a symmetric positive-definite matrix; throws std::invalid_argument naming
 * `what` if it is not positive definite. */
Eigen::MatrixXd spdInverse(const Eigen::MatrixXd& A, const std::string& what);
}  // namespace dynslam::framework
