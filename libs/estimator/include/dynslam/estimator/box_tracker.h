#pragma once
/** @file box_tracker.h
 * Tracking of detector boxes without IDs (issue 31, item 2; doc/boxes.md), pure Eigen: the
 * association and track management of a 3-D multi-object tracker in the bird's-eye view, in
 * the manner of AB3DMOT (X. Weng, J. Wang, D. Held, K. Kitani, IROS 2020): one Kalman filter
 * per track with a constant-velocity centre, global assignment of the frame's boxes to the
 * predicted tracks (the Hungarian method, models/assignment.h) on a gated cost, and track
 * management by M-of-N birth and max-age death.
 *
 * Used twice: by the `tracker_baseline` row (the peer: the tracker alone, in the odometry
 * frame) and by the filters' box front-end (feature_labels = boxes), which gives the tracks'
 * corners persistent IDs for the classifying router and may replace a track's prediction by
 * the SLAM filter's own (overridePrediction: the joint part).
 *
 * Per track, the state in the world frame is s = (x, y, yaw, length, width, vx, vy): the centre
 * moves with constant velocity (white acceleration accel_std: Q = accel_std^2 [dt^4/4, dt^3/2;
 * dt^3/2, dt^2] per axis), the heading and the extent are random walks (yaw_std, extent_std per
 * frame); a box measures (x, y, yaw, length, width) with meas_std (plus the box's centre_cov on
 * the centre). A new track starts at its box with that covariance and velocity (0, 0) with
 * velocity_std. The yaw innovation is wrapped to (-pi, pi]. The detector's front/back
 * ambiguity: a box whose heading differs from its track's (wrapped) by more than pi/2 is turned
 * by pi before the update and reported as flipped: the track keeps its heading.
 *
 * Cost of a pair (same class only): "mahalanobis": d^2 = (c_box - c_trk)' S^-1 (c_box - c_trk)
 * with S the centre block of the innovation covariance, allowed if d^2 <= the chi-square
 * 2-dof quantile of gate_prob; "bev_iou": 1 - IoU of the box's footprint and the predicted
 * footprint (models/bev_box.h), allowed if IoU >= min_iou. Forbidden pairs are removed before
 * the assignment (models/assignment.h: first the most allowed pairs, then the least cost).
 *
 * Life of a track: a box that no track takes starts a Tentative track (if score >= min_score);
 * a Tentative track with min_hits hits within its first birth_window frames becomes Confirmed,
 * one that cannot reach that any more is deleted; a Confirmed track without a hit is Lost; a
 * track (of any state) is deleted in the frame of its max_age-th consecutive frame without a
 * hit; a hit makes a Lost track Confirmed again. Deleted tracks leave tracks(). Track IDs are
 * 0, 1, 2, ... in order of birth, never reused. A frame is one update() call (age counts them).
 *
 * AB3DMOT (github.com/xinshuoweng/AB3DMOT, read for this class): AB3DMOT_libs/model.py
 * get_param(), KITTI with PointRCNN boxes: Car 'hungar' (Hungarian), metric 'giou_3d' with
 * threshold -0.2, min_hits 3, max_age 2; Pedestrian 'greedy', giou_3d -0.4, min_hits 1,
 * max_age 4; Cyclist 'hungar', 'dist_3d' 2 m, min_hits 3, max_age 4 (the 2020 version of
 * model.py: 3-D IoU with threshold 0.01, min_hits 3, max_age 2 for every class; configs/KITTI.yml:
 * max_age 2, min_hits 3, score_threshold -10000). AB3DMOT_libs/kalman_filter.py: a 10-state
 * (x, y, z, theta, l, w, h, vx, vy, vz) constant-velocity filter per frame, P0 = 10 I with 10^4
 * on the velocities, Q = I with 0.01 on the velocities, R = I (filterpy's defaults), no dt.
 * model.py orientation_correction(): when the predicted and the observed heading differ by more
 * than pi/2 (and less than 3 pi/2) the *track's* heading is turned by pi. model.py output():
 * a track is reported if time_since_update < max_age and (hits >= min_hits or frame_count <=
 * min_hits), and deleted when time_since_update >= max_age; hits count all hits (no window).
 * Ours differ: in the bird's-eye view (no z, no height; BEV IoU instead of 3-D IoU / GIoU);
 * the Mahalanobis gate as an option; physical noise per second (accel_std) and dt from the
 * stamps; the *box* is turned by pi, not the track; gated pairs are forbidden before the
 * assignment (AB3DMOT assigns on all pairs, then drops those under the threshold); the M-of-N
 * window (AB3DMOT's rule is birth_window >= min_hits + (min_hits - 1)(max_age - 1): 5 for 3
 * and 2, where a tentative track dies of max_age before the window ends); reporting (which
 * tracks a row outputs) is the caller's (the tracker_baseline row reproduces model.py
 * output()). */
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace dynslam::estimator
{
enum class ETrackState
{
	Tentative,
	Confirmed,
	Lost
};

struct TBoxTrackerParams
{
	/** Cost of a (track, box) pair: "mahalanobis" (the squared Mahalanobis distance of the box
	 * centre to the track's predicted centre, gated by the chi-square 2-dof quantile gate_prob)
	 * or "bev_iou" (1 - the BEV IoU of the box and the predicted footprint, allowed if the IoU
	 * is >= min_iou). Boxes and tracks of different classes never pair. */
	std::string metric = "mahalanobis";
	double gate_prob = 0.99;  ///< in (0, 1)
	double min_iou = 0.01;    ///< in (0, 1]
	int min_hits = 3;         ///< M of the birth rule, >= 1
	int birth_window = 3;     ///< N of the birth rule, >= min_hits
	int max_age = 2;          ///< >= 1
	double min_score = -std::numeric_limits<double>::infinity();
	double accel_std = 3.0;     ///< [m/s^2] white acceleration of the centre, > 0
	double yaw_std = 0.1;       ///< [rad per frame], > 0
	double extent_std = 0.05;   ///< [m per frame], > 0
	double velocity_std = 5.0;  ///< [m/s] prior std of a new track's velocity, > 0
	/** Box noise: centre x, y [m], heading [rad], length, width [m]; each > 0. */
	Eigen::Matrix<double, 5, 1> meas_std =
	    (Eigen::Matrix<double, 5, 1>() << 0.3, 0.3, 0.15, 0.3, 0.15).finished();
	/** Throws std::invalid_argument naming the member. */
	void validate() const;
};

/** A box in the world frame (the caller places it with its ego pose). */
struct TWorldBox
{
	Eigen::Vector3d pose = Eigen::Vector3d::Zero();    ///< centre x, y [m], yaw [rad]
	Eigen::Vector2d extent = Eigen::Vector2d::Zero();  ///< length, width [m], > 0
	std::string cls;
	double score = 0;
	/** Extra covariance of the centre from the caller's placement (e.g. the ego pose's), added
	 * to meas_std's; zero allowed. */
	Eigen::Matrix2d centre_cov = Eigen::Matrix2d::Zero();
};

using Vector7d = Eigen::Matrix<double, 7, 1>;
using Matrix7d = Eigen::Matrix<double, 7, 7>;

struct TBoxTrack
{
	int32_t id = -1;
	ETrackState state = ETrackState::Tentative;
	std::string cls;
	Vector7d x = Vector7d::Zero();  ///< (x, y, yaw, length, width, vx, vy), world frame
	Matrix7d P = Matrix7d::Zero();
	int hits = 0;          ///< frames with a box
	int age = 0;           ///< update() frames since birth (0 in its first frame)
	int misses = 0;        ///< consecutive frames without a box
	bool updated = false;  ///< a box this frame
	double score = 0;      ///< the score of its last box
};

/** What update() did with the frame's boxes. */
struct TBoxAssignment
{
	std::vector<int32_t> track;  ///< per box: the track it went to (or started), -1: ignored
	std::vector<bool> flipped;   ///< per box: turned by pi to match its track's heading
	size_t births = 0, confirmations = 0, deletions = 0;
};

class CBoxTracker
{
public:
	/** Throws std::invalid_argument on invalid params. */
	explicit CBoxTracker(const TBoxTrackerParams& params);

	/** Predicts every track by dt [s] (> 0, finite; else std::invalid_argument) and clears the
	 * previous frame's overrides. */
	void predict(double dt);
	/** After predict(), for this frame only: the predicted centre and its covariance of track
	 * id come from the caller (the SLAM filter's estimate of that object or static box) for
	 * the association and the update. The rest of the track's state follows by Jeffrey's rule
	 * (its distribution given the centre is kept: mean r + P_rc P_cc^-1 (c' - c), cross-covariance
	 * P_rc P_cc^-1 C', so the result stays positive definite). Throws std::invalid_argument for
	 * an unknown id, a non-finite centre or a covariance that is not symmetric positive
	 * definite. */
	void overridePrediction(int32_t id, const Eigen::Vector2d& centre, const Eigen::Matrix2d& cov);
	/** Associates the frame's boxes with the predicted tracks, updates, starts, confirms and
	 * deletes tracks (one frame). Throws std::invalid_argument, before any change, for a box with
	 * a non-finite pose, extent or centre_cov, a NaN score, a length or width <= 0, or a
	 * centre_cov that is not symmetric positive semi-definite. */
	TBoxAssignment update(const std::vector<TWorldBox>& boxes);

	/** The live tracks (not deleted), in order of birth. */
	const std::vector<TBoxTrack>& tracks() const { return m_tracks; }
	const TBoxTrackerParams& params() const { return m_params; }

private:
	/** The cost matrix (tracks x boxes; +inf: forbidden pairs). */
	Eigen::MatrixXd costs(const std::vector<TWorldBox>& boxes) const;
	void updateTrack(TBoxTrack& t, const TWorldBox& box, bool flip) const;
	/** Hit / miss bookkeeping of one track after this frame's assignment; true: delete it. */
	bool manage(TBoxTrack& t, bool hit, TBoxAssignment& out) const;

	TBoxTrackerParams m_params;
	std::vector<TBoxTrack> m_tracks;
	int32_t m_nextId = 0;
};
}  // namespace dynslam::estimator
