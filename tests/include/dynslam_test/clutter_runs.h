#pragma once
/** Runs of the dynamic EKF on the simulated worlds with clutter and track breaks, shared by the
 * pruning (tests/framework/prune_clutter_test.cpp) and the fusion tests
 * (tests/ekf/test_landmark_fusion_run.cpp, test_landmark_fusion_long.cpp):
 *  - their filter: highwayFilterIni (highway_filter_setup.h);
 *  - runSteps(ekf, s, gt, onStep): every step of s, onStep(k, ms) after it (ms: the step's wall
 *    time), and the ego ATE (RMS of the position error against gt). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>

#include <Eigen/Core>
#include <chrono>
#include <cmath>

namespace dynslam_test
{
template <class OnStep>
double runSteps(dynslam::CDynamicKFSLAM2D& ekf, const dynslam::sim::TSimulatedRun& s,
                const dynslam::io::TGroundTruth& gt, OnStep&& onStep)
{
	double se = 0;
	for (size_t k = 0; k < s.actions.size(); ++k)
	{
		const auto t0 = std::chrono::steady_clock::now();
		ekf.processActionObservation(s.actions[k], s.frames[k]);
		onStep(k, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
		              .count());
		const auto p = ekf.getEgoPose().mean;
		se += (Eigen::Vector2d(p.x(), p.y()) - gt.ego[k].head<2>()).squaredNorm();
	}
	return std::sqrt(se / double(s.actions.size()));
}
}  // namespace dynslam_test
