#pragma once
/** @file detection_boxes.h
 * Detector boxes in the rawlog (issue 31, item 1; doc/formats.md "Detector boxes"), written as
 * MRPT observations so that MRPT's tools read them and any MRPT program can produce them. A
 * step with boxes holds, in its sensory frame:
 *  - the CObservationBearingRange of the step, whose readings include the four footprint
 *    corners of every box (front-left, front-right, rear-right, rear-left in the box frame:
 *    x along the heading, y to its left), with landmarkID = -1 (MRPT's "association unknown");
 *  - a DETECTION_GROUPS comment (dynslam/common/detection_groups.h) giving each corner its box's
 * group;
 *  - a mrpt::obs::CObservationComment whose sensorLabel is "DETECTION_BOXES" and whose text is
 *    one line per box,
 *
 *        <group> <class> <score> <x> <y> <yaw> <length> <width>
 *
 *    group: the detection group of its corners (>= 0, unique in the step); class: one word
 *    (e.g. Car); score: the detector's confidence; (x, y) [m] the footprint centre and yaw [rad]
 *    the heading of the length axis, in the sensor frame; length, width [m] > 0. Numbers are
 *    written with 17 significant digits (a round trip is exact). The comment's text starts with
 *    the line DETECTION_BOXES: that line is how readers find it, as for DETECTION_GROUPS (MRPT's
 *    CObservationComment does not serialize sensorLabel: read back, it is empty); empty lines
 *    and lines starting with '#' are ignored.
 * MRPT's CRangeBearingKFSLAM2D sees only the corners (with unknown IDs); the project's box
 * front-end (estimator/box_tracker.h) reads the boxes. */
#include <dynslam/estimator/readings.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <string>
#include <vector>

namespace dynslam
{
constexpr const char* kDetectionBoxesLabel = "DETECTION_BOXES";

/** The comment of one step's boxes. Throws std::invalid_argument for a group < 0 or repeated,
 * an empty class or one with white space, a non-finite number, or a length or width <= 0. */
mrpt::obs::CObservationComment::Ptr makeDetectionBoxes(
    const std::vector<estimator::TBoxDetection>& boxes);

/** The four footprint corners of a box (sensor frame), in the order of the file comment. */
std::vector<Eigen::Vector2d> boxCorners(const estimator::TBoxDetection& box);

/** The boxes of SF's DETECTION_BOXES comment (none: empty). Throws std::runtime_error, prefixed
 * by `who` and naming the line, for a malformed line (column count, a token that is not a
 * number, NaN/Inf, a length or width <= 0, a group < 0 or repeated). */
std::vector<estimator::TBoxDetection> readDetectionBoxes(const mrpt::obs::CSensoryFrame& SF,
                                                         const std::string& who);

/** The consistency of a step's boxes with its readings (parseStepInput calls it): every box's
 * group must be the hint of exactly four readings, each with landmark ID -1 (its corners, in
 * observation order FL, FR, RR, RL: the order is not checked). Throws std::runtime_error,
 * prefixed by `who` and naming the box (index in the comment, group, class), otherwise.
 * Readings with ID -1 whose hint is no box's group are allowed (the existing unknown-ID
 * readings); steps without boxes are not checked. */
void checkBoxCorners(const std::vector<estimator::TBoxDetection>& boxes,
                     const std::vector<estimator::TReading>& readings, const std::string& who);
}  // namespace dynslam
