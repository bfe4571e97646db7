#pragma once
/** @file detection_import.h
 * Detection mode of the importer (`dynslam-kitti --detections DIR --calib DIR`, issue 31 item
 * 3; doc/kitti.md section 1, doc/formats.md "Detector boxes"): the kept detections of every
 * frame (detection_files.h: classes of detection_classes, score >= detection_min_score) become
 * the step's boxes (estimator::TBoxDetection, ego = sensor frame) and their footprint corners the
 * step's only readings (landmark ID -1, group = the box's group); the rawlog writer adds the
 * DETECTION_GROUPS and DETECTION_BOXES comments (dynslam/common/detection_boxes.h). Pure C++/Eigen.
 *
 * - Frame: as the labels (geometry.h): the bottom centre (x, y, z) of the camera frame is the ego
 *   point (z, -x), the yaw -rot_y - pi/2 (wrapped to (-pi, pi]); extent = (l, w); class = the
 *   detector's class (Car, Pedestrian, Cyclist); score as in the file.
 * - Filter: a box is written when its footprint centre is within max_range of the sensor (the
 *   range the observation declares); no field-of-view filter (a detector sees what it sees:
 *   PointRCNN's Car boxes reach bearings of 57.6 deg on 0001, cars at the image edge). Boxes
 *   beyond max_range are counted (TDetectionSummary::beyond_range).
 * - Groups: the running index of the written box in the sequence (0, 1, ... by frame, then class
 *   in the order of detection_classes, then file order): unique in the rawlog, so a group never
 *   suggests that two boxes are one object.
 * - No noise is added (the detector's errors are the noise); the corners are exact in double
 *   and stored as MRPT's float range and bearing. */
#include <dynslam/estimator/readings.h>
#include <dynslam/kitti/detection_files.h>
#include <dynslam/kitti/import.h>

#include <vector>

namespace dynslam::kitti
{
/** A detection as a box in the ego (sensor) frame. */
estimator::TBoxDetection egoBoxOfDetection(const TKittiDetection& d, int32_t group);

/** Replaces the readings of every step of `res` (one per frame) by the boxes of `kept`
 * (kept[k]: the kept detections of frame k, readDetectionSet's output) within max_range; sets
 * res.detections and the written counts of `summary`. Throws std::invalid_argument if kept has
 * more frames than res has steps. */
void applyDetections(const std::vector<std::vector<TKittiDetection>>& kept, double max_range,
                     TImportResult& res, TDetectionSummary& summary);
}  // namespace dynslam::kitti
