#pragma once
/** @file live_merge.h
 * (Internal to dynslam::ekf.) The live-merge module (classify_merge_live with a router that
 * classifies; doc/results/classification.md "Merging two live objects"). AfterCommit: every pair
 * of objects seen in the step is tested (estimator::CLiveMergeDetector) on B's features expressed
 * in A's frame, f' = g_A^-1(xi_A, g_B(xi_B, f^B)) (models::mergeObjectFeatures, the map the merge
 * applies), with their covariance J P J^T from the filter's joint covariance, and, with an
 * object-centric model, the velocity residual (models::rigidVelocityResidual); a pair decided
 * rigid is merged by the state surgery mergeObjects (state_surgery.h). */
#include <dynslam/estimator/live_merge.h>

#include <memory>

#include "filter_module.h"

namespace dynslam::ekf
{
class CLiveMergeModule : public IFilterModule
{
public:
	explicit CLiveMergeModule(std::unique_ptr<estimator::CLiveMergeDetector> d)
	    : m_detector(std::move(d))
	{
	}
	std::string name() const override { return "live_merge"; }
	unsigned hooks() const override { return hookBit(Hook::AfterCommit); }
	void afterCommit(TFilterAccess& a) override;

private:
	std::unique_ptr<estimator::CLiveMergeDetector> m_detector;
};

/** The module if classify_merge_live is set and the router classifies (null otherwise). */
std::unique_ptr<CLiveMergeModule> makeLiveMergeModule(TFilterAccess& a);
}  // namespace dynslam::ekf
