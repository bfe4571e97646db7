#pragma once
/** Internal: the ground-truth part of importSequence (import_gt.cpp). */
#include <dynslam/kitti/import.h>

#include <map>
#include <utility>

namespace dynslam::kitti::detail
{
/** Fills res.gt and res.track_steps (rules in import.h). read[i]: box i is read. */
void fillGroundTruth(const TKittiLabels& L, const std::vector<Eigen::Vector3d>& ego,
                     const std::vector<uint8_t>& read,
                     const std::map<std::pair<int, int>, int32_t>& ids, const TImportOptions& o,
                     TImportResult& res);
}  // namespace dynslam::kitti::detail
