#pragma once
/** @file import.h
 * Conversion of one KITTI tracking sequence into filter steps and ground truth (pure C++/Eigen;
 * the rawlog is written by rawlog_writer.h). Rules (also in doc/kitti.md):
 *
 * - Steps: one per pose line (frame k = step k), t_k = k dt. World frame = the ego frame of
 *   frame 0 (geometry.h), so the filters start at (0, 0, 0) with zero covariance.
 * - Odometry: step 0 a zero increment with zero covariance; step k the exact relative 2-D pose
 *   ego_{k-1} (-) ego_k plus, with odometry_noise = gaussian, a draw of N(0, C_k) added to
 *   (dx, dy, dphi); C_k = diag(s_xy^2, s_xy^2, s_phi^2), s_xy = odo_std_xy + odo_std_xy_per_m d,
 *   s_phi = odo_std_phi + odo_std_phi_per_m d, d = |(dx, dy)| of the exact increment. C_k is
 *   written with the action in both noise modes.
 * - Readings: a box is read at its frame when its footprint centre is within max_range and
 *   |bearing| <= fov/2; then its four footprint corners (geometry.h order) are written as
 *   range-bearing readings, each with N(0, std_range^2), N(0, std_bearing^2) added
 *   (noise = gaussian) or as annotated (noise = none: the annotation jitter only). Boxes out of
 *   range or field of view are counted. DontCare lines and boxes without 3-D data are skipped
 *   by the reader and counted.
 * - Classes (classify.h): every track is static or moving for its whole life.
 * - IDs, labelled mode: corner c of a static track T is the static landmark 4 T + c; corner c
 *   of a moving track is object feature ids::objectFeatureId(o, c), o = the track's object
 *   index (moving tracks that are read, numbered 0, 1, ... by first reading, ties by track ID).
 *   Anonymous mode: every read corner of every track gets an ID in 0 .. N-1 (N = read corners)
 *   from a permutation drawn with `seed`; the ID says nothing about the track, the corner or the
 *   class (all IDs lie in the static range, so a filter that reads IDs sees landmarks only).
 * - Ground truth (ground_truth.h): ego per step; landmarks = the static tracks' corners at
 *   their mean world position over all annotated frames (under their IDs of the mode);
 *   objects = the moving tracks (index o), 4 features = the world corners at annotated
 *   frames (NaN where the track is not annotated), visible = read at that step, first_step =
 *   first step read, pose xi_k = (c_k - c_0, yaw_k - yaw_0) at annotated steps from first_step
 *   on (c = footprint centre = the centroid of the 4 corners, the g^o rotation centre), NaN
 *   elsewhere. Extra files: the track list, the per-step class truth, the ID table
 *   (rawlog_writer.h). */
#include <dynslam/estimator/readings.h>
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/ground_truth.h>
#include <dynslam/kitti/kitti_files.h>

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace dynslam::kitti
{
enum class ENoise
{
	Gaussian,
	None
};

/** Defaults: the values of config/kitti.ini (a test checks that both agree), except
 * pose_scale: the default is auto (issue 31: the ground truth consistent by default), while
 * config/kitti.ini pins pose_scale = 1 (the annotation protocol whose tables in doc/kitti.md
 * section 5 were measured at scale 1). */
struct TImportOptions
{
	double dt = 0.1;                  ///< [s] frame period (KITTI: 10 Hz)
	double max_range = 40;            ///< [m] boxes whose centre is farther are not read
	double fov_deg = 90;              ///< [deg] full horizontal field of view, centred forward
	double static_radius = 2.0;       ///< [m] classify.h
	ENoise noise = ENoise::Gaussian;  ///< readings
	ENoise odometry_noise = ENoise::Gaussian;  ///< odometry
	uint32_t seed = 1;                         ///< noise draws and the anonymous permutation
	double std_range = 0.1;                    ///< [m] added noise; written as sensor_std_range
	double std_bearing = 0.005;                ///< [rad] added noise; written as sensor_std_yaw
	double odo_std_xy = 0.01;                  ///< [m]
	double odo_std_xy_per_m = 0.02;            ///< [m/m]
	double odo_std_phi = 0.002;                ///< [rad]
	double odo_std_phi_per_m = 0.001;          ///< [rad/m]
	bool anonymous = false;
	/** detection_groups: each step also writes a DETECTION_GROUPS comment
	 * (dynslam/common/detection_groups.h): every corner's group is its KITTI track ID (the box it
	 * belongs to), the optional hint of the classifying filter. Off: the rawlog is unchanged. */
	bool detection_groups = false;
	/** The camera trajectory's positions are multiplied by pose_scale (headings unchanged; the
	 * world origin is frame 0's position, so the path is scaled about it): 1 = as given. With
	 * pose_scale_auto, pose_scale is ignored and the factor is 1 / trajectory_scale of an
	 * import at scale 1 (TImportSummary: the least-squares fit of the trajectory to the static
	 * boxes' geometry), so that the ground truth, the odometry and the box readings agree;
	 * without a static track of >= 10 frames the factor stays 1 (reported). INI: pose_scale =
	 * auto (the default) or a number > 0. */
	double pose_scale = 1.0;
	bool pose_scale_auto = true;
};

/** One track (persistent KITTI track ID). */
struct TTrack
{
	int track = -1;
	std::string type;
	bool moving = false;
	double radius = 0;  ///< classify.h [m]
	int first_frame = -1, last_frame = -1;
	size_t frames = 0;       ///< annotated frames
	size_t read_frames = 0;  ///< frames at which it is read
	int first_read = -1;     ///< first frame read (-1: never)
	int object = -1;         ///< object index (moving tracks that are read), else -1
	double length = 0, width = 0;
	std::vector<size_t> boxes;  ///< indices into TKittiLabels::boxes, by frame
};

struct TReading
{
	int32_t id = 0;
	double range = 0, bearing = 0;
	int track = -1, corner = 0;
};

struct TStep
{
	double t = 0;
	Eigen::Vector3d increment = Eigen::Vector3d::Zero();  ///< noisy (dx, dy, dphi)
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
	std::vector<TReading> readings;  ///< the annotated boxes' corners (empty in detection mode)
	/** Detection mode (detection_import.h): the detector's boxes of the frame, ego frame; the
	 * rawlog then holds their corners (ID -1) as the step's only readings. */
	std::vector<estimator::TBoxDetection> boxes;
};

/** One row of the ID table: what a reading ID is. */
struct TIdRow
{
	int32_t id = 0;
	int track = -1, corner = 0;
	bool moving = false;
};

/** Per-step class truth: one row per annotated (frame, track). */
struct TTrackStepRow
{
	int step = 0, track = -1;
	bool moving = false, read = false;
	Eigen::Vector3d pose = Eigen::Vector3d::Zero();  ///< footprint centre and yaw, world
	double length = 0, width = 0;                    ///< the box's size at this frame [m]
};

struct TImportSummary
{
	std::string sequence;
	size_t steps = 0, label_rows = 0, dontcare = 0, no3d = 0, boxes = 0;
	size_t boxes_read = 0, out_of_range = 0, out_of_fov = 0, readings = 0;
	size_t tracks = 0, static_tracks = 0, moving_tracks = 0, tracks_never_read = 0;
	std::map<std::string, size_t> types;          ///< TKittiLabels::types
	std::map<std::string, size_t> unknown_types;  ///< TKittiLabels::unknown_types
	double path_length = 0;                       ///< [m] of the 2-D ego path
	/** The annotation jitter, measured on the static tracks (their true motion is zero):
	 * frame-to-frame motions between consecutive frames where the track is read (body frame,
	 * as eval::objectErrors scores objects): n, RMSE of |translation| [m] and |rotation| [rad];
	 * and the rms distance of the read corners from their mean world position [m]. */
	size_t floor_n = 0;
	/** Scale of the camera trajectory relative to the labels (a diagnostic, not applied): the
	 * least-squares s with ego_b - ego_a = s (R_a c_a - R_b c_b) over the static tracks with
	 * >= 10 frames (a, b = their first and last frame, c = footprint centre in the ego frame).
	 * 1 if the trajectory and the boxes agree; > 1: the trajectory is longer than the boxes'
	 * geometry says. NaN without such tracks. */
	double trajectory_scale = 0;
	/** The factor applied to the trajectory's positions (TImportOptions::pose_scale), and, with
	 * pose_scale = auto, trajectory_scale of the import at scale 1 (NaN otherwise). */
	double pose_scale = 1, trajectory_scale_unscaled = std::numeric_limits<double>::quiet_NaN();
	bool pose_scale_auto = false;
	double floor_trans_rmse = 0, floor_rot_rmse = 0, static_corner_rms = 0;
	std::string detections_text;  ///< the detection counts (CKittiApp), appended by toText
	std::string toText() const;
};

struct TImportResult
{
	std::vector<TStep> steps;
	io::TGroundTruth gt;
	std::map<int, TTrack> tracks;
	std::vector<TIdRow> ids;  ///< sorted by ID
	std::vector<TTrackStepRow> track_steps;
	TImportSummary summary;
	/** Detection mode (detection_import.h): the steps' readings are the detector's boxes
	 * (TStep::boxes), not the annotations; the ground truth is still the labels'. */
	bool detections = false;
};

/** Runs the conversion. Throws std::runtime_error / std::invalid_argument on inconsistent
 * input (labels beyond the poses, a track ID too large for the static ID range, bad options). */
TImportResult importSequence(const std::vector<TCameraPose>& poses, const TKittiLabels& labels,
                             const TImportOptions& opts, const std::string& sequence);

/** The class truth of every reading (class_ground_truth.h; written as B_gt_classes.csv), one
 * row per reading in the order of its step: id = the ID in the rawlog (either mode), true_id =
 * the labelled mode's ID (4 track + corner for a static track, ids::objectFeatureId(object,
 * corner) for a moving one), class = the track's class (classify.h: static or moving for its
 * whole life; KITTI has no clutter), object = the object index of a moving track (-1 static),
 * feature = true_id for a static track, the corner for a moving one. */
std::vector<io::TReadingClass> readingClasses(const TImportResult& res);
}  // namespace dynslam::kitti
