#pragma once
/** @file fusion.h
 * (Internal to dynslam::ekf.) The landmark-fusion module (fuse_landmarks_prob; issue 29 item 1;
 * the rule in estimator/landmark_fusion.h, doc/robustness.md "Fusing re-identified landmarks").
 * AfterRoute: readings of a fused ID read as the landmark it was fused into. AfterCommit: the
 * static landmarks read in the step are tested against their neighbours; a pair that is one
 * point is fused by state surgery through the state helper: the conditioning on
 * m_keep = m_gone (state::condition, a noise-free update on the difference), then `gone` leaves
 * the state (commit's removal, the marginalization). Its last estimate is recorded like a
 * dropped landmark (record_dropped), its ID is read as `keep` from the next step on.
 * StaticForgotten: the rule forgets a landmark that left the state. */
#include <dynslam/estimator/landmark_fusion.h>

#include <memory>
#include <vector>

#include "filter_module.h"

namespace dynslam::ekf
{
class CLandmarkFusionModule : public IFilterModule
{
public:
	explicit CLandmarkFusionModule(double prob) : m_fusion(prob) {}
	std::string name() const override { return "landmark_fusion"; }
	unsigned hooks() const override
	{
		return hookBit(Hook::AfterRoute) | hookBit(Hook::AfterCommit) |
		       hookBit(Hook::StaticForgotten);
	}
	void afterRoute(TFilterAccess& a) override;   ///< fused IDs read as their landmark
	void afterCommit(TFilterAccess& a) override;  ///< the step's fusions
	void staticForgotten(int32_t id) override { m_fusion.forget(id); }
	/** Every fusion so far (record_dropped). */
	const std::vector<estimator::TFusionPair>& fusions() const { return m_fusions; }

private:
	estimator::CLandmarkFusion m_fusion;
	std::vector<estimator::TFusionPair> m_fusions;
	std::vector<int32_t> m_used;  ///< scratch of afterRoute
};

/** The module if fuse_landmarks_prob enables it (null otherwise); throws std::invalid_argument
 * with a state lifecycle that keeps landmarks out of the state. */
std::unique_ptr<CLandmarkFusionModule> makeLandmarkFusionModule(TFilterAccess& a);
}  // namespace dynslam::ekf
