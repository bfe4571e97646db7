#pragma once
// Private pieces of rawlog_io.cpp: the objects of a file in order, the two pairings.
#include <dynslam/apps/rawlog_io.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/serialization/CSerializable.h>

#include <string>
#include <vector>

namespace dynslam::apps::detail
{
struct TEntry
{
	size_t index = 0;  ///< position in the file (0-based)
	mrpt::serialization::CSerializable::Ptr obj;
};

/** "rawlog 'path'" for messages. */
inline std::string rawlogWhat(const std::string& path) { return "rawlog '" + path + "'"; }

/** Throws if the observation's sensorLocationOnRobot is not finite, or a reading's range, yaw
 * or pitch is not finite or its range negative (named by entry, measurement and landmark ID):
 * when the file is read, before any output exists. */
void checkSensorPose(const mrpt::obs::CObservationBearingRange& obs, const std::string& path,
                     size_t entry);

/** Format #1: MRPT's readActionObservationPair pairing (rawlog_io.h). */
void pairActionsAndFrames(const std::vector<TEntry>& entries, TRawlog& out);
/** Format #2: odometry + bearing-range observations to pairs (rawlog_format2.cpp). */
void convertObservationsOnly(const std::vector<TEntry>& entries, const TOdometryNoiseOptions& noise,
                             TRawlog& out);
}  // namespace dynslam::apps::detail
