#pragma once
/** @file writers.h
 * Text outputs of a run: TUM trajectory (for evo), per-step / per-landmark / per-object CSV with
 * ground-truth and 3-sigma columns, the metrics CSV (one row per filter) and a terminal table,
 * NEES/NIS series and summaries. All CSV files have one header row; NaN / unavailable cells are
 * empty. Angles in radians. */
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/estimates.h>
#include <dynslam/eval/gap_metrics.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/eval/mot_metrics.h>
#include <dynslam/eval/velocity_metrics.h>

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace dynslam::eval
{
/** Opens `path` for writing (throws std::runtime_error naming the path if it cannot) and calls
 * write(stream). */
void writeFile(const std::string& path, const std::function<void(std::ostream&)>& write);

/** TUM trajectory, one line per ego estimate sorted by step: "t x y z qx qy qz qw" with z = 0,
 * q = (0, 0, sin(theta/2), cos(theta/2)). t = the estimate's t if finite, else gt->t[step];
 * throws std::invalid_argument if neither is available. */
void writeTum(std::ostream& os, const std::vector<TEgoEstimate>& ego,
              const io::TGroundTruth* gt = nullptr);

/** Per-step ego CSV: step,t,x,y,theta,sigma3_x,sigma3_y,sigma3_theta,gt_x,gt_y,gt_theta,
 * err_x,err_y,err_theta,nees,nis,nis_dof (gt/err/nees columns empty without ground truth;
 * nees empty where the covariance is singular). Sorted by step. */
void writeEgoCsv(std::ostream& os, const TRunEstimates& est, const io::TGroundTruth* gt = nullptr);

/** Landmarks CSV: id,x,y,sigma3_x,sigma3_y,gt_x,gt_y,err_x,err_y,nees (sorted by ID). */
void writeLandmarksCsv(std::ostream& os, const TRunEstimates& est,
                       const io::TGroundTruth* gt = nullptr);

/** Object features (time 0) CSV: object,feature,x,y,sigma3_x,sigma3_y,gt_x,gt_y,err_x,err_y. */
void writeObjectFeaturesCsv(std::ostream& os, const TRunEstimates& est,
                            const io::TGroundTruth* gt = nullptr);

/** Object poses CSV: object,step,t,dx,dy,dtheta,sigma3_dx,sigma3_dy,sigma3_dtheta,gt_dx,gt_dy,
 * gt_dtheta,err_dx,err_dy,err_dtheta,nees,dof (theta columns empty for 2-dof poses). */
void writeObjectPosesCsv(std::ostream& os, const TRunEstimates& est,
                         const io::TGroundTruth* gt = nullptr);

/** Object motion CSV (models with a velocity state): object,step,t,vx,vy,omega,sigma3_vx,
 * sigma3_vy,sigma3_omega, then p_<mode> per est.object_mode_names (object_model = mm): the
 * velocity, the turn rate and the mode probabilities of every object pose that has a velocity
 * (omega empty for 2-dof poses). */
void writeObjectMotionCsv(std::ostream& os, const TRunEstimates& est,
                          const io::TGroundTruth* gt = nullptr);

/** One filter's row of the metrics CSV / table. */
struct TMetricsRow
{
	std::string filter;  ///< e.g. static_all, static_landmarks_only, dynamic
	TRunMetrics metrics;
	std::optional<TConsistencySummary> consistency;  ///< adds the NEES/NIS columns if set
	/** Classification scores (feature_labels = classify rows, class_metrics.h): per-reading
	 * precision, recall, F1 of "moving" and the grouping ARI. */
	struct TClassScores
	{
		double precision = kNaN, recall = kNaN, f1 = kNaN, ari = kNaN;
	};
	std::optional<TClassScores> classes;  ///< if any row has it: 4 more columns (see below)
	/** The ego inside the scenario's landmark gaps (gap_metrics.h): if any row has it, the
	 * last 7 columns (see below). */
	std::optional<TGapMetrics> gap;
	/** Object velocities of a model with a velocity state (velocity_metrics.h): if any row has
	 * it, 4 more columns after the gap columns (see below). */
	std::optional<TVelocityErrors> velocity;
	/** The process's peak memory in MiB (peak_memory.h; dynslam-run): if any row has it, one
	 * more column, the last (see below). */
	std::optional<double> peak_rss_mb;
	/** Multi-object tracking of the row's box tracks (issue 31; mot_metrics.h; dynslam-compare
	 * on a KITTI import with detections): CLEAR MOT with pairs matched by BEV IoU >= 0.25 and
	 * by centre distance <= 2 m, sAMOTA by BEV IoU, one class. If any row has it, 12 more
	 * columns, the last (see below). */
	struct TMotScores
	{
		std::string cls;
		TMotCounts iou, dist;
		double samota = kNaN;
	};
	std::optional<TMotScores> mot;
};

/** Metrics CSV: a header row, then one row per filter. Columns:
 * filter,ego_rmse_x,ego_rmse_y,ego_rmse_theta,static_rmse_x,static_rmse_y,ate,ate_aligned,ms_per_step,
 * ego_steps,landmarks_scored,landmarks_missing,landmarks_unmatched,
 * for each agent k = 1..K (K = most objects in any row): agentk_object,agentk_feat_rmse_x,
 * agentk_feat_rmse_y,agentk_pose_rmse_x,agentk_pose_rmse_y,agentk_pose_rmse_theta,
 * then (only if a row has TMetricsRow::classes; empty for the other rows)
 * class_precision,class_recall,class_f1,group_ari,
 * then ego_anees,ego_nees_inside,map_anees,map_dof,nis_anees,nis_inside (fractions in [0,1];
 * empty without consistency), then odometry_bias_rate_final [rad/s], odometry_bias_scale_final
 * (the final odometry bias estimate, TRunMetrics; empty without a bias state / scale), then
 * (only if a row has TMetricsRow::gap; empty for the other rows) ate_gap,ate_outside_gap,
 * err_gap_end,steps_gap,ego_nees_gap,ego_nees_gap_lower,ego_nees_gap_upper, then (only if a
 * row has TMetricsRow::velocity; empty for the other rows) obj_speed_rmse [m/s],
 * obj_omega_rmse [rad/s],obj_velocity_anees,obj_velocity_n, then (only if a row has
 * TMetricsRow::peak_rss_mb; empty for the other rows) peak_rss_mb [MiB], then (only if a row
 * has TMetricsRow::mot; empty for the other rows) mot_class,mota,motp,ids,frag,fp,fn,gt,samota
 * (BEV IoU >= 0.25; motp: the mean IoU), mota_d2,motp_d2,ids_d2 (centre distance <= 2 m; motp_d2:
 * the mean distance [m]). */
void writeMetricsCsv(std::ostream& os, const std::vector<TMetricsRow>& rows);

/** The same numbers as an aligned plain-text table for the terminal. */
void writeMetricsTable(std::ostream& os, const std::vector<TMetricsRow>& rows);

/** One NEES/NIS series: key,runs,total_dof,mean,lower,upper,inside. */
void writeConsistencyCsv(std::ostream& os, const TConsistencyStats& stats);

/** Text summary, one line per block: samples, ANEES with bounds, % of rows inside. */
void writeConsistencySummary(std::ostream& os, const TConsistencySummary& s);

/** NEES/NIS summary CSV over several labelled summaries (e.g. one per noise level):
 * label,block,runs,rows,anees,anees_lower,anees_upper,inside,fraction_inside,skipped_singular,
 * one row per block (ego, landmarks, map, object<k>_pose..., nis). */
void writeConsistencySummaryCsv(
    std::ostream& os, const std::vector<std::pair<std::string, TConsistencySummary>>& summaries);
}  // namespace dynslam::eval
