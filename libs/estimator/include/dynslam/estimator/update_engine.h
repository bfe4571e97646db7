#pragma once
/** @file update_engine.h
 * Seam 3 of the estimator core (doc/architecture.md): the static update (Alg. 5) with the
 * tracked static landmarks read in a step. Implementations: CSparseUpdateEngine (the EKF
 * update as a symmetric rank-2k correction on the non-zero columns of H, default) here, the
 * robust engines (robust_update_engines.h), and MRPT's own update (CKalmanFilterCapable's
 * kfEKFNaive / kfEKFAlaDavison) and JCBB in libs/ekf. How the state is stored between steps
 * (e.g. compressed) is a seam of its own, state_lifecycle.h. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/measurement.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace dynslam::estimator
{
/** A reading of a tracked static landmark whose x-coordinate is at state index `index`. */
struct TStaticObservation
{
	int32_t id;
	Eigen::Vector2d z;
	int index;
};

struct TUpdateContext
{
	models::MeasurementModel model = models::MeasurementModel::Cartesian;
	Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
	/** The sensor's pose on the robot (x, y, yaw): readings are z = h(x (+) s, f). */
	Eigen::Vector3d sensor_pose = Eigen::Vector3d::Zero();
	/** A reading whose squared Mahalanobis distance (its own 2x2 innovation covariance)
	 * exceeds this is not used, and counted. Infinity: no gate. */
	double gate_threshold = std::numeric_limits<double>::infinity();
	/** Optional: replaces the Jacobians J_z_x, J_z_f of landmark `id` at ego pose `ego` and
	 * the sensor pose sensor_pose (first-estimate Jacobians); the innovation stays at the
	 * current estimate. */
	std::function<void(int32_t id, const Eigen::Vector3d& ego, models::Matrix23d& J_z_x,
	                   Eigen::Matrix2d& J_z_f)>
	    jacobians;
};

struct TUpdateResult
{
	size_t updates = 0, gated_out = 0;
	double nis = 0;  ///< NIS of the readings used (0 if none)
	size_t nis_dof = 0;
};

class IUpdateEngine
{
public:
	virtual ~IUpdateEngine() = default;
	virtual std::string name() const = 0;
	/** Updates (x, P) in place with the readings; the ego pose is x[0..2]. */
	virtual TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                             const std::vector<TStaticObservation>& obs,
	                             const TUpdateContext& ctx) = 0;
	/** Whether the engine updates the (x, P) it is given, reading and writing through the
	 * readings' entries and the ego only (a linear Kalman update of the whole Gaussian): then
	 * it composes with every state lifecycle (state_lifecycle.h). False for an engine bound to
	 * its filter's own storage (MRPT's). */
	virtual bool updatesGivenState() const { return true; }
};

/** The sparse symmetric update (ekf::sparseUpdate): O(n^2 k) for k readings. */
class CSparseUpdateEngine : public IUpdateEngine
{
public:
	std::string name() const override { return "sparse"; }
	TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                     const std::vector<TStaticObservation>& obs,
	                     const TUpdateContext& ctx) override;

private:
	// The step's temporaries, kept between steps (cleared, capacity kept): no allocation per step
	// once the largest sizes have been seen.
	std::vector<int> m_idx;
	std::vector<models::Matrix23d> m_Jx;
	std::vector<Eigen::Matrix2d> m_Jf;
	std::vector<Eigen::Vector2d> m_nus;
};

/** Chi-square quantile with 2 dof in closed form (F(x) = 1 - exp(-x/2)) of probability p;
 * infinity for p = 0 (no gate). */
double gateThreshold2Dof(double p);
}  // namespace dynslam::estimator
