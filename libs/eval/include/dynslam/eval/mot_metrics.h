#pragma once
/** @file mot_metrics.h
 * Multi-object tracking metrics in the bird's-eye view (pure C++/Eigen; doc/metrics.md
 * "Multi-object tracking"):
 *
 * - CLEAR MOT (K. Bernardin, R. Stiefelhagen, "Evaluating Multiple Object Tracking
 *   Performance: The CLEAR MOT Metrics", EURASIP JIVP 2008), frame by frame:
 *   1. every truth object o whose last correspondence (o, h) (the mapping M; kept across frames
 *      where o or h is missing) is still valid in this frame (h present, not yet taken, the
 *      pair matches) keeps it;
 *   2. the remaining truths and hypotheses are assigned by the Hungarian method
 * (models/assignment.h: most pairs that match, then least total distance);
 *   3. a new correspondence (o, h') with o's last correspondence h != h' is a mismatch (ids);
 *   truths left unmatched are misses (fn), hypotheses left unmatched false positives (fp).
 *   mota = 1 - (fn + fp + ids) / gt; motp = the mean over the matched pairs of the centre
 *   distance [m] (criterion CentreDistance: Bernardin's definition) or of the BEV IoU
 *   (criterion BevIoU: the KITTI devkit's and AB3DMOT's convention, higher is better).
 *   frag (Y. Li, C. Huang, R. Nevatia, CVPR 2009; not part of CLEAR MOT): the number of times
 *   a truth object that has been matched before is matched again after one or more of its own
 *   frames unmatched (frames where it is not annotated do not count).
 * - A pair matches when the classes are equal and, by criterion, the centre distance is
 *   <= max_distance or the BEV IoU of the oriented footprints (models/bev_box.h) is >= min_iou.
 * - sAMOTA (X. Weng, J. Wang, D. Held, K. Kitani, "3D Multi-Object Tracking: A Baseline and
 *   New Evaluation Metrics", IROS 2020): for the recall levels r = 1/L, 2/L, ..., 1, the
 *   hypotheses are thresholded on their score so that the recall reaches r, CLEAR MOT is run on
 *   the kept ones, and sMOTA_r = max(0, 1 - (ids_r + fp_r + fn_r - (1 - r) gt) / (r gt));
 *   sAMOTA = the mean over the L levels. Threshold of level r: the ceil(r gt)-th highest score
 *   among the hypotheses matched when all are kept (keep score >= it); a level that needs more
 *   matches than that run has gets sMOTA_r = 0. (AB3DMOT's code picks the score whose recall
 *   is nearest to r; with ceil the level is reached, never undershot: the choice differs by at
 *   most one match per level.)
 * Not modelled: KITTI's DontCare regions and its ignored classes (Van for Car, ...); the
 * caller selects what to score (selectClass). */
#include <dynslam/core/models/bev_box.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace dynslam::eval
{
/** The footprint and its overlap live in libs/core (models/bev_box.h), shared with the box
 * tracker; named here as before. */
using models::bevCentreDistance;
using models::bevIoU;
using models::TBevBox;

enum class EMotCriterion
{
	CentreDistance,
	BevIoU
};

struct TMotOptions
{
	EMotCriterion criterion = EMotCriterion::BevIoU;
	double max_distance = 2.0;  ///< [m] CentreDistance: a pair matches if distance <= this
	double min_iou = 0.25;      ///< BevIoU: a pair matches if IoU >= this
	int recall_levels = 40;     ///< L of sAMOTA (AB3DMOT: 40)
};

/** One box of a frame: a truth object or a hypothesis (a tracker's output). IDs are unique per
 * frame within truths and within hypotheses; score is used by sAMOTA (hypotheses only). */
struct TMotObject
{
	int id = -1;
	std::string cls;
	TBevBox box;
	double score = 0;
};

struct TMotFrame
{
	std::vector<TMotObject> truth, hyp;
};

struct TMotCounts
{
	size_t frames = 0, gt = 0, hyp = 0;
	size_t tp = 0, fp = 0, fn = 0, ids = 0, frag = 0;
	double mota = std::numeric_limits<double>::quiet_NaN();  ///< NaN when gt = 0
	double motp = std::numeric_limits<double>::quiet_NaN();  ///< NaN when tp = 0
};

struct TSamota
{
	double samota = std::numeric_limits<double>::quiet_NaN();  ///< NaN when gt = 0
	std::vector<double> recall;                                ///< r of each level
	std::vector<double> threshold;  ///< its score threshold (NaN: level unreachable)
	std::vector<double> smota;      ///< sMOTA_r
};

/** Throws std::invalid_argument on bad options, a duplicate ID within a frame's truths or
 * hypotheses, or a box bevIoU rejects (criterion BevIoU). */
TMotCounts clearMot(const std::vector<TMotFrame>& frames, const TMotOptions& opts);
TSamota samota(const std::vector<TMotFrame>& frames, const TMotOptions& opts);
/** The frames with only the truths and hypotheses of class cls. */
std::vector<TMotFrame> selectClass(const std::vector<TMotFrame>& frames, const std::string& cls);
}  // namespace dynslam::eval
