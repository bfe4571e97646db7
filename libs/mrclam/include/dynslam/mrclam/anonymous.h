#pragma once
/** @file anonymous.h
 * `dynslam-mrclam --anonymous` (issue 12, doc/results/real-data.md section 6): the readings carry
 * IDs that say nothing about what was measured, and the class ground truth of every reading.
 *
 * Anonymous IDs: the 20 MRCLAM subjects (robots 1..5, landmarks 6..20) are mapped by a seeded
 * random permutation onto 0..19, one range for both kinds, so neither the value nor the range
 * of an ID tells a robot (a moving object) from a landmark. The permutation is a Fisher-Yates
 * shuffle driven by std::mt19937(seed) with j = rng() mod (i + 1), so it is the same on every
 * standard library (std::shuffle is not). The ego's own subject keeps its slot but never occurs.
 *
 * Class ground truth (dynslam/io/class_ground_truth.h, `<base>_gt_classes.csv`, written for
 * labelled and anonymous imports alike): one row per kept measurement, in rawlog order; id =
 * the ID written; true_id = the labelled ID (landmark subject s: s; robot r:
 * ids::objectFeatureId(r, 0)); class = static for landmarks, moving for robots (every robot
 * reading, also while that robot stands still: the robots are the moving objects of the data
 * set); object = the robot's subject number, feature 0 (landmarks: object -1, feature = s). */
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/mrclam/import.h>

#include <cstdint>
#include <map>
#include <vector>

namespace dynslam::mrclam
{
/** Subject 1..20 -> anonymous ID 0..19 (a permutation, see the file comment). */
std::map<int, int32_t> anonymousSubjectIds(uint32_t seed);

/** The labelled ID of a subject (landmark s: s; robot r: ids::objectFeatureId(r, 0)). */
int32_t labelledSubjectId(int subject);

/** Rewrites the ID of every measurement of res with anonymousSubjectIds(seed), keys the
 * landmark truth res.gt.landmarks by the same IDs (B_gt_landmarks.csv then scores the map of an
 * anonymous run; the objects keep their indices = robot subjects) and records the map in
 * res.summary.anonymous_ids. Throws std::logic_error if res is already anonymous. */
void makeAnonymous(TImportResult& res, uint32_t seed);

/** The class ground truth of every kept measurement, in rawlog order (file comment). */
std::vector<io::TReadingClass> classGroundTruth(const TImportResult& res);
}  // namespace dynslam::mrclam
