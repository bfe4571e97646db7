#pragma once
/** @file import.h
 * Conversion of one MRCLAM robot's data into filter steps and ground truth (pure, no MRPT;
 * the rawlog is written by rawlog_writer.h). Rules (also in doc/results/real-data.md):
 *
 * - Time window: from the first measurement that the ground truth covers to the last one;
 *   with clip_to_ground_truth, the window is limited to where the Vicon data of all five
 *   robots exist (so every exported truth is interpolated, never extrapolated); `duration`
 *   (> 0) further limits it to [t_first, t_first + duration]. Measurements outside: dropped,
 *   counted as outside_window.
 * - Steps: measurements are grouped in file (time) order; a group starts at the first
 *   measurement not yet grouped and takes every later one with t - t_start <= group_window.
 *   The step's time is t_start. Groups with no valid measurement make no step.
 * - Barcodes that map to no subject: dropped, counted (spurious). The ego's own barcode:
 *   dropped, counted (own_barcode). A subject read twice in one group: the first reading (in
 *   file order, i.e. the earliest) is kept, the others dropped and counted (duplicates).
 * - IDs: landmark subjects 6..20 keep their subject number as static ID; robot subject r
 *   becomes the one-feature moving object r: ID = ids::objectFeatureId(r, 0).
 * - World frame: the ego's ground-truth pose at the first step (the origin, in Vicon
 *   coordinates, is reported). So the filter starts at (0, 0, 0) with zero covariance, like
 *   MRPT's CRangeBearingKFSLAM2D, and all ground truth is expressed in that frame.
 * - Odometry: step 0 has a zero increment with zero covariance; step k > 0 the exact
 *   integration (odometry.h, with odometry_delay and the gains) from t_{k-1} to t_k, with
 *   TOdometryNoiseModel's covariance.
 * - Ground truth per step: ego pose interpolated at t_k; landmarks; each other robot r as
 *   object r with one feature (its interpolated position at t_k), visible = measured at step
 *   k, first_step = first step it was measured, pose = (p_k - p_first_step, 0) from
 *   first_step on (NaN before). io::TGroundTruth stores object i at index i, so objects 0..5 are
 *   exported: object 0 and the ego's own index are placeholders (never visible, NaN). */
#include <dynslam/io/ground_truth.h>
#include <dynslam/mrclam/mrclam_files.h>
#include <dynslam/mrclam/odometry.h>

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dynslam::mrclam
{
/** Defaults: the Dataset 6 values of config/mrclam.ini (estimated with --estimate-noise,
 * doc/results/real-data.md); a test checks that both agree. */
struct TImportOptions
{
	TImportOptions();
	double group_window = 0.05;  ///< [s] measurements within this of a group's start: one step
	double max_range = 10.0;     ///< [m] maxSensorDistance written into each observation
	double duration = 0;         ///< [s] > 0: only the first `duration` seconds of steps
	bool clip_to_ground_truth = true;  ///< window within every robot's Vicon coverage
	double std_range = 0.155;          ///< [m] written as sensor_std_range
	double std_bearing = 0.0106;       ///< [rad] written as sensor_std_yaw
	double odometry_delay = 0.2;       ///< [s] command latency d (odometry.h)
	double odometry_scale_v = 0.95;    ///< gain on v (odometry.h)
	double odometry_scale_w = 1;       ///< gain on w (odometry.h)
	TOdometryNoiseModel odometry_noise;
};

struct TStepMeasurement
{
	int subject;
	int32_t id;                ///< landmark ID written into the rawlog
	double t, range, bearing;  ///< own time [s], [m], [rad]
	int line;                  ///< line in the measurement file
};

struct TStep
{
	double t = 0;  ///< step time [s] (time of the group's first measurement)
	std::vector<TStepMeasurement> meas;
	TOdometryIncrement increment;                   ///< from the previous step (zero for step 0)
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();  ///< covariance of the increment
};

struct TImportSummary
{
	std::string dataset;
	int ego = 0;
	size_t rows = 0;  ///< measurement rows in the file
	size_t kept = 0;
	size_t spurious = 0;  ///< barcodes that map to no subject
	size_t own_barcode = 0;
	size_t duplicates = 0;
	size_t outside_window = 0;
	std::map<int, size_t> per_subject;  ///< kept measurements per subject
	std::map<int, size_t> spurious_per_barcode;
	size_t steps = 0;
	double t_first = 0, t_last = 0;  ///< first / last step time [s]
	double duration() const { return t_last - t_first; }
	double max_range_seen = 0;  ///< [m] among kept measurements
	double max_gt_gap = 0;      ///< [s] largest Vicon gap (any robot) inside the window
	Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< ego Vicon pose at step 0
	/** --anonymous (anonymous.h): subject -> the ID written; empty for labelled IDs. */
	std::map<int, int32_t> anonymous_ids;
	uint32_t anonymous_seed = 0;  ///< the permutation's seed (anonymous imports)
	size_t landmarkMeasurements() const;
	size_t robotMeasurements() const;
	/** Human-readable, stable text (printed by the app and saved beside the rawlog). */
	std::string toText() const;
};

struct TImportResult
{
	std::vector<TStep> steps;
	io::TGroundTruth gt;
	TImportSummary summary;
};

/** Runs the conversion. Throws std::runtime_error on inconsistent data (e.g. a barcode of a
 * landmark without ground truth, no measurement inside the ground truth's time span). */
TImportResult importRobot(const TDataset& data, const TImportOptions& opts);
}  // namespace dynslam::mrclam
