#pragma once
/** @file filter_run.h
 * Running any back-end (ISlamBackend) over a sequence of (action, sensory frame) pairs and
 * collecting its estimates as plain data (dynslam::eval::TRunEstimates), plus the back-end
 * factory used by the apps. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/eval/estimates.h>
#include <mrpt/config/CConfigFileBase.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace dynslam::apps
{
/** Back-end kinds the apps can build: "ekf" (the dynamic EKF, CDynamicKFSLAM2D, sections
 * [DynamicKFSLAM] and [DynamicKFSLAM_KalmanFilter]), "static_all" and "static_landmarks_only"
 * (MRPT's CRangeBearingKFSLAM2D, CStaticBaselineBackend, sections [RangeBearingKFSLAM] and
 * [RangeBearingKFSLAM_KalmanFilter]), "odometry" (dead reckoning, CDeadReckoningBackend) and
 * "tracker_baseline" (AB3DMOT's method on the detector boxes, CTrackerBaselineBackend, section
 * [BoxTracker]; both take [DynamicKFSLAM] if present), and the optimization framework's back-ends
 * (dynslam/framework/backend_factory.h: alg1, vdo, dynaslam2, cubeslam, clusterslam_*; section
 * [Backend] plus the model section, default [DynamicKFSLAM]). */
const std::vector<std::string>& backendKinds();

/** Builds and configures a back-end of the given kind. If `optionsDump` is given, the
 * effective options of every options struct of the back-end are written to it. Throws
 * std::invalid_argument for an unknown kind or a bad option (message names section and key). */
std::unique_ptr<ISlamBackend> makeBackend(const std::string& kind,
                                          const mrpt::config::CConfigFileBase& ini,
                                          std::ostream* optionsDump = nullptr);

/** What one pass of a back-end over a rawlog produced. */
struct TFilterRun
{
	std::string name;            ///< back-end name (tables, file names)
	eval::TRunEstimates est;     ///< ego per step (t = NaN), final map, objects, NIS, ms_per_step
	std::vector<double> stamps;  ///< per step: time stamp of the observation [s], NaN if none
	double total_ms = 0;         ///< wall time inside processActionObservation(), all steps
	size_t steps = 0;
};

/** Feeds pair k to the back-end for k = 0..n-1, recording the ego estimate after each step,
 * then the final map and object estimates. Only the back-end's own processing is timed.
 * progress(done, total) is called after each step (if set), and before it stepTime(step, ms)
 * with the wall time of that step's processActionObservation (if set). Errors of the back-end
 * are rethrown as std::runtime_error naming the back-end and the step. */
TFilterRun runFilter(ISlamBackend& backend,
                     const std::vector<mrpt::obs::CActionCollection::Ptr>& actions,
                     const std::vector<mrpt::obs::CSensoryFrame::Ptr>& frames,
                     const std::function<void(size_t, size_t)>& progress = {},
                     const std::function<void(size_t, double)>& stepTime = {});

/** The final map and object estimates of a back-end (landmarks with their joint covariance
 * when the back-end exposes it, time-0 object features, every recorded object pose). */
void collectFinalEstimates(const ISlamBackend& backend, eval::TRunEstimates& est);
}  // namespace dynslam::apps
