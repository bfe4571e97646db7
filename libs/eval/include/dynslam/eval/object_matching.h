#pragma once
/** @file object_matching.h
 * Object scores of the rows that classify (feature_labels = classify; doc/metrics.md "Objects
 * of classifying rows"). Their object numbers are the classifying router's (numbered in the
 * order the router confirms them, a new number after a track break), not the truth's, so the
 * object columns cannot match estimate and truth by number. Instead every estimated object is
 * matched to a true object by the class ground truth of its readings (class_ground_truth.h).
 * Pure Eigen. */
#include <dynslam/class_ground_truth.h>
#include <dynslam/eval/estimates.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/eval/velocity_metrics.h>
#include <dynslam/ground_truth.h>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace dynslam::eval
{
/** Estimated object -> true object. estObject[i]: the estimator's object of reading i (-1: not
 * an object reading), truth[i]: that reading's ground truth (same order and size; throws
 * std::invalid_argument otherwise). An estimated object gets the true object most of its
 * readings belong to, counting readings of no true object (static landmarks, clutter: truth
 * object -1) as a candidate too; ties go to the smallest true object number >= 0, so -1 (no
 * true match) wins only with strictly more readings than every true object. Several estimated
 * objects may get the same true object (e.g. the two halves of a track break). */
std::map<int32_t, int32_t> matchObjectsByReadings(const std::vector<int32_t>& estObject,
                                                  const std::vector<TReadingClass>& truth);

/** The estimates with every object number replaced by its match (objects not in the map or
 * matched to -1 get -1: no truth has it, so the scores skip them). */
TRunEstimates withMatchedObjects(const TRunEstimates& est, const std::map<int32_t, int32_t>& match);

/** Velocity errors of a classifying run (object_model = cv | ctrv): objectVelocityErrors on the
 * matched estimates; nullopt (empty cells) without a class ground truth (truth == nullptr) or
 * without velocities. */
std::optional<TVelocityErrors> classifyingVelocityErrors(const TGroundTruth& gt,
                                                         const TRunEstimates& est,
                                                         const std::vector<int32_t>& estObject,
                                                         const std::vector<TReadingClass>* truth);

/** Empties the agent_* feature and pose RMSE cells (NaN) of a classifying row: the router's
 * feature indices and first-sighting frames are not the truth's, so these numbers would compare
 * unrelated quantities. The agent_<k>_object numbers (the truth's) stay. */
void blankObjectColumns(TRunMetrics& m);
}  // namespace dynslam::eval
