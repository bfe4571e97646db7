#pragma once
/** @file detection_groups.h
 * Optional per-reading hints of a front-end (issue 12: "a reading may carry an object /
 * detection group, e.g. a box ID"), written in the rawlog as MRPT observations so any MRPT
 * program can produce them: beside the step's CObservationBearingRange, the sensory frame
 * holds a mrpt::obs::CObservationComment whose sensorLabel is "DETECTION_GROUPS" and whose
 * text is one line per grouped reading,
 *
 *     <index> <landmarkID> <group>
 *
 * index: the reading's position in the step's (first) CObservationBearingRange, 0-based;
 * landmarkID: its ID there (a check; -1 allowed); group: the detection group (box ID), >= 0.
 * Empty lines and lines starting with '#' are ignored; readings not listed have no hint.
 * Programs that do not know the label ignore the comment (MRPT's CRangeBearingKFSLAM2D does).
 * The hint is evidence for grouping only (doc/results/classification.md, "Hints"). */
#include <dynslam/estimator/readings.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dynslam
{
constexpr const char* kDetectionGroupsLabel = "DETECTION_GROUPS";

/** The comment of one step: groups[i] is the group of reading i (ID ids[i]), -1 for none
 * (not listed). Throws std::invalid_argument if the sizes differ or a group is < -1. */
mrpt::obs::CObservationComment::Ptr makeDetectionGroups(const std::vector<int32_t>& ids,
                                                        const std::vector<int32_t>& groups);

/** Sets readings[i].hint from the DETECTION_GROUPS comment of SF (none: unchanged). Throws
 * std::runtime_error, prefixed by `who` and naming the line, for a malformed line, an index out
 * of range, an ID that is not the reading's, an index listed twice or a group < 0. */
void readDetectionGroups(const mrpt::obs::CSensoryFrame& SF,
                         std::vector<estimator::TReading>& readings, const std::string& who);
}  // namespace dynslam
