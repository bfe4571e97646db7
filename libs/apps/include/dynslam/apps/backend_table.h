#pragma once
/** @file backend_table.h
 * Every back-end on the same highway Monte Carlo, measured in one run (doc/backends.md): the
 * dynamic EKF (CDynamicKFSLAM2D) and each configuration of the framework, on identical
 * rawlogs (same ground truth, same noise seeds). Metrics from dynslam::eval (Table I
 * definitions): ego RMSE over the per-step (online) estimates, static-map and time-0
 * object-feature RMSE of the final estimates, object-pose RMSE over the final estimate of
 * every pose (smoothed where the back-end keeps it, else recorded when it left the window),
 * ANEES (average NEES / dof) of the ego and of the object poses, and the wall time per step
 * (processActionObservation plus getEgoPose, i.e. including the covariance a user reads). */
#include <dynslam/framework/TBackendOptions.h>

#include <ostream>
#include <string>
#include <vector>

namespace dynslam::apps
{
struct TBackendTableOptions
{
	std::string scenario_ini;          ///< e.g. config/highway.ini
	std::string noise_level = "w2v2";  ///< eq. (5)-(7) grid
	int runs = 3;                      ///< Monte Carlo runs (noise seeds 1..runs)
	int steps = -1;                    ///< -1: the scenario's
	int window_size = 10;              ///< W of the windowed back-ends
	double sigma_xi = 0.1;             ///< Sigma_xi = sigma_xi I (paper: 0.1)
	std::vector<std::string> kinds;    ///< empty: "dynamic_ekf" and every backendKinds()
};

struct TBackendTableRow
{
	std::string kind;
	int runs = 0, failures = 0;
	std::string failure;  ///< first failure message
	double ego_x = 0, ego_y = 0, ego_theta = 0, map_x = 0, map_y = 0, feat_x = 0, feat_y = 0,
	       pose_x = 0, pose_y = 0, pose_theta = 0;
	double anees_ego = 0, anees_pose = 0;
	/** Ego RMSE (x, y) of the final trajectory (smoothed / fixed-lag; = online for filters). */
	double final_x = 0, final_y = 0;
	/** RMSE of the translation of the 10-step relative poses of the final trajectory (the
	 * common drift removed). */
	double rpe10 = 0;
	double ms_per_step = 0;
};

std::vector<TBackendTableRow> runBackendTable(const TBackendTableOptions& o);
void writeBackendTableMarkdown(std::ostream& os, const std::vector<TBackendTableRow>& rows);
}  // namespace dynslam::apps
