#pragma once
/** @file compare_mot.h
 * (Internal to dynslam-compare.) The multi-object tracking metrics of the rows that track
 * boxes (issue 31; doc/metrics.md "Multi-object tracking"): the truth of a KITTI import
 * (box_ground_truth.h) placed in the true robot frame of every step, the rows' tracked boxes
 * (ISlamBackend::trackedBoxes) in their own, both restricted to the importer's field of view
 * (max_range, fov_deg of `<base>_scenario.ini`), scored for one class. As the KITTI devkit does
 * for its neighbouring classes, a hypothesis that matches no truth of the class but matches a
 * box of a neighbouring class (Van for Car) is left out, neither a true nor a false positive. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/eval/writers.h>
#include <dynslam/io/ground_truth.h>

#include <string>
#include <vector>

namespace dynslam::apps::detail
{
struct TMotTruth
{
	bool valid = false;  ///< false: no box truth beside the rawlog (no MOT columns)
	std::string cls = "Car";
	std::vector<std::string> neighbours{"Van"};
	double max_range = 0;  ///< [m], 0: no limit
	double fov = 0;        ///< [rad], 0: no limit
	/** Per step: the boxes of cls, and of the neighbouring classes, in the region (robot frame). */
	std::vector<std::vector<eval::TMotObject>> truth, ignored;
};

/** The truth of `<base>_gt_tracks.csv` / `_gt_track_list.csv` with the ego of gt; !valid if the
 * files are missing. Throws std::runtime_error on malformed files or a step beyond gt. */
TMotTruth loadMotTruth(const std::string& base, const io::TGroundTruth& gt);

/** CLEAR MOT (BEV IoU 0.25 and centre distance 2 m) and sAMOTA (IoU) of one row's tracked boxes
 * per step (hyp[k]: step k). */
eval::TMetricsRow::TMotScores scoreMot(const TMotTruth& truth,
                                       const std::vector<std::vector<TTrackedBox>>& hyp);
/** One line of the terminal table: "tracking (Car): f: MOTA ... (BEV IoU 0.25), ... (2 m)". */
std::string motLine(const std::string& filter, const eval::TMetricsRow::TMotScores& s);
}  // namespace dynslam::apps::detail
