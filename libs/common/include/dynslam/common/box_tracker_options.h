#pragma once
/** @file box_tracker_options.h
 * Section [BoxTracker] (issue 31, doc/boxes.md "Tracker"): the keys of the box tracker
 * (estimator::CBoxTracker, estimator/box_tracker.h), shared by the `tracker_baseline` row of
 * dynslam-compare and the filters' box front-end (feature_labels = boxes), plus the output
 * rule of the tracker_baseline row. A missing key keeps the member's current value, so a
 * caller may start from other defaults (set `params` before loading); a default-constructed
 * TBoxTrackerOptions holds AB3DMOT's KITTI Car parameters (ab3dmotParams()). Unknown keys,
 * values out of range and bad words are errors naming [section] and the key.
 *
 * Keys (TBoxTrackerParams, in the order of box_tracker.h): metric (mahalanobis | bev_iou),
 * gate_prob, min_iou, min_hits, birth_window, max_age, min_score, accel_std [m/s^2], yaw_std
 * [rad per frame], extent_std [m per frame], velocity_std [m/s], meas_std (5 numbers: x, y [m],
 * yaw [rad], length, width [m]); the tracker_baseline row's report_lost and
 * report_first_frames. */
#include <dynslam/estimator/box_tracker.h>
#include <mrpt/config/CLoadableOptions.h>

#include <iosfwd>
#include <string>

namespace dynslam
{
/** AB3DMOT's parameters for KITTI Car (AB3DMOT_libs/model.py and configs/KITTI.yml; the
 * header comment of box_tracker.h): the IoU metric with threshold 0.01 (its 2020 release: 3-D
 * IoU; ours BEV), min_hits 3, max_age 2, and birth_window 5 = min_hits + (min_hits - 1)(max_age
 * - 1), which makes max_age the only death rule of a tentative track as in AB3DMOT. The noise
 * keys keep TBoxTrackerParams' defaults (AB3DMOT's filter has unit-less identity noise per
 * frame, not comparable). */
estimator::TBoxTrackerParams ab3dmotParams();

struct TBoxTrackerOptions : public mrpt::config::CLoadableOptions
{
	estimator::TBoxTrackerParams params = ab3dmotParams();
	/** tracker_baseline's output (trackedBoxes): also Lost tracks (confirmed, not updated this
	 * step, not yet deleted: AB3DMOT's model.py output() reports every track with
	 * time_since_update < max_age and hits >= min_hits). false: only tracks updated this step. */
	bool report_lost = true;
	/** tracker_baseline's output: in the first min_hits steps every live track, Tentative ones
	 * included (AB3DMOT's "or frame_count <= min_hits"). */
	bool report_first_frames = true;

	/** The output rule (both the tracker_baseline row and feature_labels = boxes): whether track
	 * t is reported at the `frame`-th step (1-based): Confirmed and updated, or Lost with
	 * report_lost, or any live track in the first min_hits steps with report_first_frames. */
	bool reports(const estimator::TBoxTrack& t, int frame) const;

	/** Reads [section] (see the file comment); validates. Throws std::invalid_argument. */
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
	                        const std::string& section) override;
	void dumpToTextStream(std::ostream& out) const override;
};
}  // namespace dynslam
