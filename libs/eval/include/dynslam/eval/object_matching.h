#pragma once
/** @file object_matching.h
 * Object scores of the rows that classify (feature_labels = classify; doc/metrics.md "Objects
 * of classifying rows"). Their object numbers are the classifying router's (numbered in the
 * order the router confirms them, a new number after a track break), not the truth's, so the
 * object columns cannot match estimate and truth by number. Instead every estimated object is
 * matched to a true object by the class ground truth of its readings (class_ground_truth.h).
 * Pure Eigen. */
#include <dynslam/eval/estimates.h>
#include <dynslam/eval/metrics.h>
#include <dynslam/eval/velocity_metrics.h>
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/ground_truth.h>

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
                                                  const std::vector<io::TReadingClass>& truth);

/** The estimates with every object number replaced by its match (objects not in the map or
 * matched to -1 get -1: no truth has it, so the scores skip them). */
TRunEstimates withMatchedObjects(const TRunEstimates& est, const std::map<int32_t, int32_t>& match);

/** Velocity errors of a classifying run (object_model = cv | ctrv): objectVelocityErrors on the
 * matched estimates; nullopt (empty cells) without a class ground truth (truth == nullptr) or
 * without velocities. */
std::optional<TVelocityErrors> classifyingVelocityErrors(
    const io::TGroundTruth& gt, const TRunEstimates& est, const std::vector<int32_t>& estObject,
    const std::vector<io::TReadingClass>* truth);

/** Empties the agent_* feature and pose RMSE cells (NaN) of a classifying row (without a class
 * ground truth, nothing tells which estimated object is which true one). The agent_<k>_object
 * numbers (the truth's) stay. */
void blankObjectColumns(TRunMetrics& m);

/** The estimator's object and feature of every reading of a classifying run, in rawlog order
 * (TRoutedReading::object and ::feature; -1: not an object reading). */
struct TReadingObjects
{
	std::vector<int32_t> object, feature;
};

/** How one true object (agent) of a classifying row was scored (scoreClassifyingAgents). */
struct TAgentMatch
{
	int32_t truth = -1;           ///< the true object (io::TObjectGroundTruth::object)
	int32_t estimated = -1;       ///< the estimated object scored against it; -1: none
	size_t candidates = 0;        ///< estimated objects matched to it (matchObjectsByReadings)
	size_t readings = 0;          ///< readings of `estimated` that belong to the true object
	int first_step = -1;          ///< `estimated`'s time 0: the step of its first reading
	size_t features_matched = 0;  ///< features of `estimated` matched to a true feature
};

/** The agent_* feature and pose RMSE cells of a classifying row (doc/metrics.md "Objects of
 * classifying rows"). Every true object T of gt is scored against ONE estimated object: among
 * those matched to T by matchObjectsByReadings, the one with the most readings of T (tie: the
 * smaller number); none: T's cells stay empty (NaN). That object E was founded at step s (the
 * step of its first reading); each feature j of E is matched to the true feature of T most of
 * the readings (E, j) belong to (readings of anything else count as "none", which wins only
 * with strictly more; ties: the smaller feature).
 *  - features: E's time-0 estimates f_0 (its own time 0) against the matched true features'
 *    positions at s; features_missing = T's features without a matched estimate;
 *  - poses: E's pose at step k (relative to s, about c_e = the centroid of its founders' f_0,
 *    g^o of object_pose.h) against T's motion from s to k in that convention: the world-frame
 *    rigid motion G_k = T_k o T_s^-1 of T's truth applied to c = the centroid at s of the true
 *    features matched to E's founders (E's readings at s): (G_k(c) - c, wrap(dtheta_k -
 *    dtheta_s)); theta from 3-dof estimates only, as for the labelled rows.
 * Founded at T's first sighting with all of T's features, this is exactly the labelled rows'
 * scoring (computeRunMetrics). Replaces m.objects (one per gt object, gt order); returns how
 * each agent was matched. Throws std::invalid_argument if reads and truth differ in size. */
std::vector<TAgentMatch> scoreClassifyingAgents(TRunMetrics& m, const io::TGroundTruth& gt,
                                                const TRunEstimates& est,
                                                const TReadingObjects& reads,
                                                const std::vector<io::TReadingClass>& truth);
}  // namespace dynslam::eval
