#pragma once
/** @file realdata_run.h
 * Evaluation of the three filters of dynslam-compare on imported MRCLAM data
 * (doc/results/real-data.md, section 5), shared by the end-to-end test (test_realdata) and the
 * development tool dynslam-realdata-report (scripts/mrclam_results.sh).
 *
 * Besides the metrics of dynslam::apps::evaluateRun it records, per step, what the apps do not:
 *  - the static updates rejected by the dynamic filter's innovation gate (TStepReport);
 *  - the dynamic filter's online estimate of every other robot: for a one-feature object the
 *    position at step t is p_t = f_0 + xi_t, read from the state right after step t (mean and
 *    joint covariance of the two blocks) at every step where the robot was measured, and
 *    compared with its ground-truth position at step t. The robot sightings never update the
 *    state (Alg. 3-4 only augment), so p_t is the measurement placed from the ego estimate. */
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace dynslam::realdata
{
/** The online position estimate of one tracked robot at one step. */
struct TTrackedPosition
{
	int object = -1;  ///< object index (MRCLAM subject number of the robot)
	int step = 0;
	Eigen::Vector2d est = Eigen::Vector2d::Zero(), truth = Eigen::Vector2d::Zero();
	Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
	double nees = 0;  ///< (est - truth)^T cov^-1 (est - truth), 2 dof
};

/** Summary of one tracked robot (object index = MRCLAM subject number). */
struct TTrackedSummary
{
	int object = -1;
	size_t n = 0;               ///< steps with an estimate and a finite truth
	double rmse = 0;            ///< sqrt(mean |est - truth|^2) [m]
	double mean_nees = 0;       ///< 2 if consistent
	double frac_nees_in95 = 0;  ///< fraction with NEES < chi2_2(0.95) = 5.99
};

/** One filter on one rawlog. */
struct TRealDataResult
{
	std::string filter;  ///< static_all | static_landmarks_only | dynamic | dynamic_nogate
	apps::TFilterRun run;
	apps::TEvaluation eval;
	size_t gated_out = 0;       ///< static updates rejected by the gate (dynamic only)
	size_t static_updates = 0;  ///< static updates used (dynamic only)
	double ate = 0;             ///< ego ATE [m] (no alignment; the world frame is the true start)
	double landmark_rmse = 0;   ///< sqrt(rmse_x^2 + rmse_y^2) of the final static map [m]
	size_t landmarks_scored = 0;
	std::vector<TTrackedPosition> tracked;  ///< dynamic filters: every robot, every sighting
	std::map<int, TTrackedSummary> tracked_by_robot;
	TTrackedSummary tracked_all;  ///< all robots pooled (object = -1)
};

/** Runs one filter: "static_all", "static_landmarks_only", "dynamic" (the INI as given) or
 * "dynamic_nogate" (the same with [DynamicKFSLAM] innovation_gate = 0 and outlier_method =
 * none). Throws on errors. */
TRealDataResult runRealData(const apps::TRawlog& rawlog, const io::TGroundTruth& gt,
                            const mrpt::config::CConfigFileMemory& ini, const std::string& filter);

/** Summary of the tracked positions of one object (object >= 0) or of all (object = -1). */
TTrackedSummary summarizeTracked(const std::vector<TTrackedPosition>& v, int object);
}  // namespace dynslam::realdata
