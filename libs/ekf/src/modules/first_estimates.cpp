/** The first-estimate Jacobians module (first_estimates.h). */
#include "first_estimates.h"

#include <set>

namespace dynslam::ekf
{
std::unique_ptr<CFirstEstimateModule> makeFirstEstimateModule(TFilterAccess& a)
{
	if (!a.options().first_estimate_jacobians) return nullptr;
	return std::make_unique<CFirstEstimateModule>();
}

void CFirstEstimateModule::endOfStep(TFilterAccess& a)
{
	// A landmark's first estimate is its mean at the end of the step that initialized it (the
	// object steps and the smoothing may move it after its augmentation in that step). A
	// dropped landmark is forgotten: if seen again, it is a new state entry with a new one.
	const auto x = a.mean();
	std::set<int32_t> inState;
	for (const auto& [id, b] : a.staticBlocks())
	{
		inState.insert(id);
		const int k = a.layout().first(b);
		m_firstEstimate.emplace(id, Eigen::Vector2d(x[k], x[k + 1]));
	}
	for (auto it = m_firstEstimate.begin(); it != m_firstEstimate.end();)
		it = inState.count(it->first) || a.lifecycle().isPassive(it->first)
		         ? std::next(it)
		         : m_firstEstimate.erase(it);
}

void CFirstEstimateModule::jacobians(models::MeasurementModel model,
                                     const Eigen::Vector3d& sensorPose, int32_t id,
                                     const Eigen::Vector3d& ego, models::Matrix23d& J_z_x,
                                     Eigen::Matrix2d& J_z_f) const
{
	const auto it = m_firstEstimate.find(id);
	if (it == m_firstEstimate.end()) return;
	models::observeFromSensor(model, ego, sensorPose, it->second, &J_z_x, &J_z_f);
}

std::optional<Eigen::Vector2d> CFirstEstimateModule::firstEstimate(int32_t id) const
{
	const auto it = m_firstEstimate.find(id);
	if (it == m_firstEstimate.end()) return std::nullopt;
	return it->second;
}
}  // namespace dynslam::ekf
