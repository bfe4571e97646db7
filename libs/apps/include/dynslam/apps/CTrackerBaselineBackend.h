#pragma once
/** @file CTrackerBaselineBackend.h
 * The `tracker_baseline` row of dynslam-compare (issue 31, item 5; doc/boxes.md "Tracker"): the
 * peer. AB3DMOT's method (estimator::CBoxTracker with AB3DMOT's parameters, section
 * [BoxTracker], dynslam/common/box_tracker_options.h) on the steps' detector boxes
 * (TStepInput::boxes), with ego-motion compensation from the odometry: the ego is the
 * dead-reckoned pose of the `odometry` row (CDeadReckoningBackend), each box is placed in the
 * world by it and the sensor's pose, x_w = ego (+) sensor (+) box. The odometry is taken as
 * exact for the placement (AB3DMOT compensates with the KITTI poses the same way): the boxes'
 * centre_cov is zero.
 *
 * Each step: the tracker predicts by the stamp difference of the step (none on the first step
 * or without increase; a step with boxes but no stamp is an error, as for the filters' box
 * front-end), then takes the boxes. trackedBoxes(): AB3DMOT's output rule (model.py output()):
 * the Confirmed tracks updated this step, and with report_lost the Lost ones (not deleted yet);
 * with report_first_frames, in the first min_hits steps every live track; each placed back in
 * the robot frame of the step by the same dead-reckoned ego, score = its last box's. */
#include <dynslam/apps/CDeadReckoningBackend.h>
#include <dynslam/common/box_tracker_options.h>
#include <dynslam/estimator/box_tracker.h>

#include <cmath>
#include <limits>
#include <memory>

namespace dynslam::apps
{
class CTrackerBaselineBackend : public CDeadReckoningBackend
{
public:
	CTrackerBaselineBackend();

	/** [DynamicKFSLAM] as the odometry row, and [BoxTracker] (missing: AB3DMOT's defaults). */
	void loadOptions(const mrpt::config::CConfigFileBase& ini) override;
	void dumpOptions(std::ostream& out) const override;
	void reset() override;

	std::string name() const override { return "tracker_baseline"; }
	std::vector<TTrackedBox> trackedBoxes() const override { return m_reported; }

	const TBoxTrackerOptions& trackerOptions() const { return m_options; }
	const estimator::CBoxTracker& tracker() const { return *m_tracker; }

protected:
	void onStep(const estimator::TStepInput& in) override;

private:
	TBoxTrackerOptions m_options;
	std::unique_ptr<estimator::CBoxTracker> m_tracker;
	double m_lastStamp = std::numeric_limits<double>::quiet_NaN();
	std::vector<TTrackedBox> m_reported;
};
}  // namespace dynslam::apps
