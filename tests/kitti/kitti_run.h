#pragma once
/** @file kitti_run.h
 * The filters of dynslam-compare on an imported KITTI sequence, with the metrics of
 * doc/kitti.md: ego ATE and RPE over 10 frames, static map RMSE, object position RMSE and the
 * object motion error in VDO-SLAM's form (eval/motion_metrics.h), static updates rejected by the
 * dynamic filter's gate, ms per step. Shared by the end-to-end test (test_kitti_excerpt) and
 * the development tool dynslam-kitti-report (scripts/kitti_results.sh). */
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/eval/motion_metrics.h>
#include <dynslam/eval/velocity_metrics.h>
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace dynslam::kitti_eval
{
struct TKittiRunResult
{
	std::string filter;  ///< static_all | static_landmarks_only | dynamic | dynamic_nogate |
	                     ///< dynamic_classified | dynamic_cv | dynamic_ctrv
	apps::TFilterRun run;
	apps::TEvaluation eval;
	double ate = 0;                ///< [m], no alignment (the world frame is the true start)
	eval::TRelativePoseError rpe;  ///< over 10 frames
	double map_rmse = 0;           ///< sqrt(rmse_x^2 + rmse_y^2) of the final static map [m]
	size_t landmarks_scored = 0;
	eval::TObjectErrors objects;  ///< dynamic only
	/** Object velocities (object_model = cv | ctrv: dynamic_cv, dynamic_ctrv); nullopt for the
	 * filters without a velocity state. */
	std::optional<eval::TVelocityErrors> velocity;
	/** The same two on the steps where the object was read (gt visible) only: a model with a
	 * velocity state also predicts objects out of view (coasting), the paper's model keeps
	 * their last pose; scored on the seen steps, the filters are compared like for like. */
	eval::TObjectErrors objects_seen;
	std::optional<eval::TVelocityErrors> velocity_seen;
	size_t gated_out = 0, static_updates = 0;
	/** dynamic_classified with a class truth given: "moving" per reading and per track, and the
	 * grouping ARI (eval/class_metrics.h). */
	eval::TBinaryScores class_reading, class_track;
	double group_ari = std::nan("");
};

/** Runs one filter of config/compare_kitti.ini's rows on the rawlog, or "dynamic_nogate" (the
 * dynamic filter with [DynamicKFSLAM] innovation_gate = 0, like MRPT's ungated filter).
 * classes: the class truth of every reading (<base>_gt_classes.csv), scored when the filter
 * classifies (dynamic_classified); may be empty. */
TKittiRunResult runKitti(const apps::TRawlog& rawlog, const io::TGroundTruth& gt,
                         const mrpt::config::CConfigFileMemory& ini, const std::string& filter,
                         const std::vector<io::TReadingClass>& classes = {});
}  // namespace dynslam::kitti_eval

namespace dynslam::kitti_eval
{
/** Dead reckoning: the rawlog's odometry increments composed from the origin (no filter), with
 * ATE and RPE as for the filters: the reference a filter should beat. */
struct TOdometryOnly
{
	double ate = 0;
	eval::TRelativePoseError rpe;
};
TOdometryOnly deadReckoning(const apps::TRawlog& rawlog, const io::TGroundTruth& gt);
}  // namespace dynslam::kitti_eval
