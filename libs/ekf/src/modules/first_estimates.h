#pragma once
/** @file first_estimates.h
 * (Internal to dynslam::ekf.) The first-estimate Jacobians module (first_estimate_jacobians).
 * AfterPropagate: records the predicted ego pose x_{k|k-1}, the linearisation point of the next
 * step's prediction (the facade's propagateEgo reads predictedEgo()). EndOfStep: records the mean
 * of static landmarks without a first estimate and forgets those no longer in the state. The
 * static update's Jacobians of a landmark are those at (ego, its first estimate) (jacobians(),
 * read by the facade's updateContext). */
#include <dynslam/core/models/measurement.h>

#include <map>
#include <memory>
#include <optional>

#include "filter_module.h"

namespace dynslam::ekf
{
class CFirstEstimateModule : public IFilterModule
{
public:
	std::string name() const override { return "first_estimates"; }
	unsigned hooks() const override
	{
		return hookBit(Hook::AfterPropagate) | hookBit(Hook::EndOfStep);
	}
	void afterPropagate(TFilterAccess& a) override { m_predictedEgo = a.ego(); }
	void endOfStep(TFilterAccess& a) override;
	/** Replaces J_z_x, J_z_f of static landmark `id` by those at (ego, its first estimate);
	 * unchanged if it has none. */
	void jacobians(models::MeasurementModel model, const Eigen::Vector3d& sensorPose, int32_t id,
	               const Eigen::Vector3d& ego, models::Matrix23d& J_z_x,
	               Eigen::Matrix2d& J_z_f) const;
	/** x_{k|k-1} of the last step (null before the first prediction). */
	const Eigen::Vector3d* predictedEgo() const
	{
		return m_predictedEgo ? &*m_predictedEgo : nullptr;
	}
	/** The first estimate of static landmark `id` (empty: none). */
	std::optional<Eigen::Vector2d> firstEstimate(int32_t id) const;

private:
	std::map<int32_t, Eigen::Vector2d> m_firstEstimate;  ///< landmark ID -> first estimate
	std::optional<Eigen::Vector3d> m_predictedEgo;       ///< x_{k|k-1} of the last step
};

/** The module if first_estimate_jacobians is set (null otherwise). */
std::unique_ptr<CFirstEstimateModule> makeFirstEstimateModule(TFilterAccess& a);
}  // namespace dynslam::ekf
