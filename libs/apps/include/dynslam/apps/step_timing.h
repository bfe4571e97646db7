#pragma once
/** @file step_timing.h
 * dynslam-run's timing.csv: per step, the wall time of the back-end's step and the size of its
 * state after it, streamed to a temporary file during the run (nothing held in memory for the
 * whole run) and moved into the output folder once the run is done (a run that fails leaves
 * no output folder). Format in doc/formats.md. */
#include <dynslam/common/ISlamBackend.h>

#include <cstddef>
#include <fstream>
#include <string>

namespace dynslam::apps
{
/** One row of timing.csv. */
struct TStepTiming
{
	size_t step = 0;
	double ms = 0;                ///< wall time of processActionObservation [ms]
	size_t static_landmarks = 0;  ///< static landmarks in the state after the step
	size_t live_objects = 0;      ///< objects with at least one block in the state
	/** Entries of the filter's working state (ego, pads and, with static_update = compressed,
	 * the accumulated blocks; not the passive landmarks); 0: the back-end does not report it. */
	size_t state_dim = 0;
};

/** The state sizes of `backend` after a step into `t`: cheap counts for the EKF
 * (CDynamicKFSLAM2D), the result getters for the other back-ends (state_dim 0). */
void fillStateSize(const ISlamBackend& backend, TStepTiming& t);

/** timing.csv streamed: a header on construction, one line per write(). */
class CTimingCsv
{
public:
	/** Opens a fresh file in the system's temporary folder (throws std::runtime_error). */
	CTimingCsv();
	/** Removes the temporary file if it was not moved. */
	~CTimingCsv();
	CTimingCsv(const CTimingCsv&) = delete;
	CTimingCsv& operator=(const CTimingCsv&) = delete;
	void write(const TStepTiming& t);
	/** Closes the file and moves it to `path` (throws std::runtime_error naming the path). */
	void moveTo(const std::string& path);
	const std::string& tempPath() const { return m_temp; }

private:
	std::string m_temp;
	std::ofstream m_os;
	bool m_moved = false;
};
}  // namespace dynslam::apps
