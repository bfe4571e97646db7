#pragma once
/** @file rawlog_io.h
 * Reading MRPT rawlogs (format #1: alternating CActionCollection / CSensoryFrame, gz-compressed
 * or plain) into memory, with clear errors.
 *
 * The pairing is that of mrpt::obs::CRawlog::readActionObservationPair: everything up to the
 * next action is skipped (comments, stray observations), then everything up to the next
 * sensory frame. readActionObservationPair itself prints any deserialization error to stderr
 * and returns false, so a truncated or corrupt file would look like a shorter valid one; this
 * reader reads the objects one at a time with the same rule and throws instead. */
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <string>
#include <vector>

namespace dynslam::apps
{
/** The (action, sensory frame) pairs of a rawlog; pair k is filter step k. */
struct TRawlog
{
	std::string path;
	std::vector<mrpt::obs::CActionCollection::Ptr> actions;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	size_t entries = 0;  ///< serialized objects read (including skipped ones)
	size_t size() const { return actions.size(); }
};

/** Reads all pairs. Throws std::runtime_error naming the file when it does not exist or
 * cannot be opened, when an object cannot be deserialized (corrupt or truncated file: the
 * message gives the entry index and MRPT's reason), when an action is not followed by a
 * sensory frame, and when the file holds no pair at all. */
TRawlog loadRawlog(const std::string& path);
}  // namespace dynslam::apps
