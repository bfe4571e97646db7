#pragma once
/** @file rawlog_io.h
 * Reading MRPT rawlogs (gz-compressed or plain) into the (action, sensory frame) pairs every
 * back-end takes, with clear errors. Two layouts are accepted:
 *
 * - Format #1 (actions and sensory frames). The pairing is that of MRPT's
 *   CRawlog::readActionObservationPair, which kf-slam uses: everything up to the next action
 *   is skipped (comments, stray observations, a sensory frame before the first action), then
 *   everything up to the next sensory frame. So MRPT's simul-landmarks output (each step written
 *   as sensory frame then action: SF_0 ACT_0 SF_1 ... SF_N-1 ACT_N-1) gives the pairs
 *   (ACT_k, SF_k+1): the leading SF_0 and the trailing ACT_N-1 are dropped, each with a
 *   warning (kf-slam drops them silently). A second action before any sensory frame replaces
 *   the first, as in MRPT.
 * - Format #2 (observations only: CObservationOdometry + CObservationBearingRange, what current
 *   MRPT and the ROS bridges write). Each bearing-range observation is one step; its odometry is
 *   the last odometry reading whose timestamp is not after the observation's; the action of
 *   step k is the increment between the odometry poses of steps k-1 and k (odo_k (-) odo_k-1),
 *   with the covariance of MRPT's Gaussian motion model (TOdometryNoiseOptions, INI section
 *   [OdometryNoise]); step 0 gets a zero increment with zero covariance. Observations before the
 *   first odometry reading are dropped with a warning. Every odometry and bearing-range
 *   observation must carry a timestamp, odometry timestamps must not decrease.
 *
 * MRPT's readActionObservationPair prints any deserialization error to stderr and returns false,
 * so a truncated or corrupt file would look like a shorter valid one; this reader reads the
 * objects one at a time and throws instead. */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cmath>
#include <iosfwd>
#include <string>
#include <vector>

namespace dynslam::apps
{
/** Odometry noise for observations-only rawlogs: MRPT's Gaussian motion model
 * (mrpt::obs::CActionRobotMovement2D::TMotionModelOptions::gaussianModel, applied with
 * CActionRobotMovement2D::computeFromOdometry), section [OdometryNoise]. Defaults are MRPT's;
 * the fields have MRPT's meaning and units (a2, a3 as MRPT stores them). */
struct TOdometryNoiseOptions
{
	double a1 = 0.01;                     ///< std of x/y per metre travelled
	double a2 = 0.001 * 180 / M_PI;       ///< std of x/y per rotation (MRPT's RAD2DEG(0.001))
	double a3 = M_PI / 180;               ///< std of phi per metre travelled (MRPT's DEG2RAD(1))
	double a4 = 0.05;                     ///< std of phi per rotation
	double minStdXY = 0.01;               ///< [m] added std of x/y
	double minStdPHI = 0.2 * M_PI / 180;  ///< [rad] added std of phi (INI: minStdPHI_deg)
	/** Keys: model (only "gaussian"), a1, a2, a3, a4, minStdXY, minStdPHI_deg; all optional,
	 * unknown keys rejected, negative values rejected. */
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& section);
	void dumpToTextStream(std::ostream& out) const;
};

/** The (action, sensory frame) pairs of a rawlog; pair k is filter step k. */
struct TRawlog
{
	enum class Format
	{
		ActionsAndFrames,  ///< format #1
		ObservationsOnly   ///< format #2, converted to pairs
	};
	std::string path;
	Format format = Format::ActionsAndFrames;
	std::vector<mrpt::obs::CActionCollection::Ptr> actions;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	size_t entries = 0;  ///< serialized objects read (including skipped ones)
	/** For pair k: the index of its sensory frame (format #2: bearing-range observation) among
	 * all of them in the file, dropped ones included. MRPT's ground-truth path files
	 * (simul-landmarks) have one row per sensory frame: pair k is row frameIndex[k]. */
	std::vector<size_t> frameIndex;
	size_t framesInFile =
	    0;  ///< sensory frames (format #2: bearing-range observations) in the file
	std::vector<std::string> warnings;  ///< dropped entries etc., one sentence each
	/** What is normal in MRPT's files but dropped all the same: the leading sensory frame and
	 * the trailing action of MRPT's simul-landmarks order (SF_0 ACT_0 ... SF_N-1 ACT_N-1), which
	 * kf-slam drops too (the apps log them at DEBUG level, not as warnings). */
	std::vector<std::string> notes;
	size_t size() const { return actions.size(); }
};

/** Reads all pairs (either format; the odometry noise is used for format #2 only). Throws
 * std::runtime_error naming the file when it does not exist or cannot be opened, when an object
 * cannot be deserialized (corrupt or truncated file: the message gives the entry index and
 * MRPT's reason), when a bearing-range observation has a non-finite sensorLocationOnRobot, when
 * a format-#2 file lacks timestamps or odometry, and when the file yields no step at all. */
TRawlog loadRawlog(const std::string& path, const TOdometryNoiseOptions& odometryNoise = {});
}  // namespace dynslam::apps
