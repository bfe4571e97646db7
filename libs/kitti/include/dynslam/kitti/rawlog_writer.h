#pragma once
/** @file rawlog_writer.h
 * Writes an import (import.h) as an MRPT rawlog plus its ground truth, like the MRCLAM
 * importer (libs/mrclam/include/dynslam/mrclam/rawlog_writer.h):
 *  - rawlog format #1, gz-compressed: per step a CActionCollection with one
 *    CActionRobotMovement2D (poseChange = CPosePDFGaussian(increment, covariance),
 *    rawOdometryIncrementReading = increment, estimationMethod = emScan2DMatching so that MRPT
 *    stores the Gaussian itself: with emOdometry it would store the raw increment and rebuild
 *    the covariance from its own motion model on reading), then a CSensoryFrame with one
 *    CObservationBearingRange (label "RB", sensor at the robot origin, maxSensorDistance =
 *    max_range, fieldOfView_yaw = fov, sensor_std_range / sensor_std_yaw = std_range /
 *    std_bearing, one TMeasurement per reading: range, yaw = bearing, pitch 0, landmarkID);
 *    detection mode (TImportResult::detections, detection_import.h): the readings are the
 *    corners of the step's boxes (boxCorners order, landmarkID -1), followed by a
 *    DETECTION_GROUPS and a DETECTION_BOXES comment (dynslam/common/detection_boxes.h) in every
 * step;
 *  - `<base>_gt_*` (dynslam::io::writeGroundTruth) and the KITTI extras:
 *      `<base>_gt_tracks.csv`      step,t,track,type,moving,read,x,y,yaw (per annotated frame
 *                                  of every track: its class, whether it is read, footprint
 *                                  centre and yaw in the world frame)
 *      `<base>_gt_track_list.csv`  track,type,moving,radius,first_frame,last_frame,frames,
 *                                  read_frames,first_read,object,length,width
 *      `<base>_gt_boxes.csv`       step,t,track,type,moving,read,x,y,yaw,length,width (per
 *                                  annotated frame of every track: its box in the world frame,
 *                                  17 digits; the multi-object tracking truth)
 *      `<base>_gt_ids.csv`         id,track,corner,moving,object (every reading ID of the
 *                                  labelled/anonymous import)
 *      `<base>_gt_classes.csv`     the class truth of every reading (class_ground_truth.h,
 *                                  readingClasses in import.h): scores feature_labels = classify;
 *                                  not written in detection mode (no truth per detection)
 *  - `<base>_summary.txt` and `<base>_scenario.ini` (the effective [KITTI_Import] options, i.e.
 *    the noise used, the mode, the counts and the filter start).
 * Everything is written into a temporary folder inside `dir` and moved into place at the end:
 * on an error nothing is left behind (existing files of an earlier import are replaced only
 * when every new file was written). */
#include <dynslam/kitti/CKittiOptions.h>
#include <dynslam/kitti/import.h>

#include <string>
#include <vector>

namespace dynslam::kitti
{
/** Writes the rawlog to `path`. Throws std::runtime_error if it cannot be written. */
void writeRawlog(const TImportResult& res, const TImportOptions& opts, const std::string& path);

/** Writes every file listed above into `dir` (created if missing); returns their paths. */
std::vector<std::string> writeImport(const TImportResult& res, const TKittiOptions& opts,
                                     const std::string& dir, const std::string& base);
}  // namespace dynslam::kitti
