#pragma once
/** @file class_metrics.h
 * Metrics of online static / moving classification and grouping (issue 12), pure functions
 * on the class ground truth of every reading (class_ground_truth.h, B_gt_classes.csv) and a
 * classifier's decisions. Definitions and conventions: doc/metrics.md, section
 * "Classification and grouping". "Moving" is the positive class; static landmarks and clutter
 * are negatives. */
#include <dynslam/eval/estimates.h>
#include <dynslam/io/class_ground_truth.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dynslam::eval
{
/** A classifier's decision about one reading (Undecided scores as "not moving"). */
enum class Decision : uint8_t
{
	Static,
	Moving,
	Undecided
};

/** Binary scores of "moving". precision = tp / (tp + fp), recall = tp / (tp + fn),
 * f1 = 2 tp / (2 tp + fp + fn); each NaN when its denominator is 0. */
struct TBinaryScores
{
	size_t tp = 0, fp = 0, fn = 0, tn = 0;
	size_t undecided = 0;  ///< of all scored items, counted as "not moving"
	double precision = kNaN, recall = kNaN, f1 = kNaN;
};
/** Fills precision, recall and f1 from the counts. */
TBinaryScores finishScores(TBinaryScores s);

/** Per reading: decisions[i] is the decision about truth[i] (throws std::invalid_argument if
 * the sizes differ). */
TBinaryScores perReadingScores(const std::vector<io::TReadingClass>& truth,
                               const std::vector<Decision>& decisions);

/** Per track (written ID >= 0; rows with id -1 are not tracks and are skipped): each track is
 * scored once, at its last reading (largest step, then index): truth = that reading's class,
 * prediction = the decision about it (the final decision). */
TBinaryScores perTrackScores(const std::vector<io::TReadingClass>& truth,
                             const std::vector<Decision>& decisions);

/** One motion onset: a true feature (object, feature) whose reading at onset_step is moving
 * while its previous reading was static (a parked object drives off). With
 * includeFirstSightings, a feature whose first reading is already moving also has an onset, at
 * that reading. detect_step: the first step >= onset_step with a reading of that feature
 * decided Moving (-1: never); delay = detect_step - onset_step [steps] (-1: never). */
struct TOnsetDelay
{
	int32_t object = -1, feature = -1;
	int onset_step = -1, detect_step = -1, delay = -1;
};
struct TDelaySummary
{
	std::vector<TOnsetDelay> onsets;
	size_t detected = 0, missed = 0;
	double mean_delay = kNaN;  ///< over the detected onsets [steps]
	int max_delay = -1;        ///< over the detected onsets (-1: none detected)
};
/** Rows may come in any order; they are read by (step, index). The onset is searched only up
 * to the feature's next static reading (a stop ends the episode). */
TDelaySummary detectionDelays(const std::vector<io::TReadingClass>& truth,
                              const std::vector<Decision>& decisions,
                              bool includeFirstSightings = false);

/** Adjusted Rand index (Hubert & Arabie 1985) between two labelings of the same items:
 * ARI = (sum_ij C(n_ij,2) - E) / (0.5 (sum_i C(a_i,2) + sum_j C(b_j,2)) - E),
 * E = sum_i C(a_i,2) sum_j C(b_j,2) / C(n,2). 1 for identical partitions (up to renaming),
 * about 0 for random ones, negative below chance. When the denominator is 0 (n = 1, or both
 * partitions are a single cluster, or both all singletons) the partitions are identical and the
 * result is 1 (scikit-learn's convention). Throws std::invalid_argument on empty input or
 * different sizes. */
double adjustedRandIndex(const std::vector<int64_t>& truth, const std::vector<int64_t>& estimate);

/** Grouping purity of moving readings: the ARI between the true object and the estimated group
 * over the readings whose true class is moving. estimatedGroup[i] is the group of truth[i];
 * a negative group (not grouped, or decided static) makes that reading its own singleton
 * cluster. NaN when no reading is moving. */
double groupingAri(const std::vector<io::TReadingClass>& truth,
                   const std::vector<int64_t>& estimatedGroup);

/** Estimated object identities against the true objects (issue 29, "estimated objects"): over
 * the readings whose true class is moving, the distinct estimated groups (an object, or the
 * identity it continues after a track break: TRoutedReading::identity) and the distinct true
 * objects. An identity is impure when its readings come from two or more true objects; a true
 * object is split when its readings fall into two or more identities. Negative groups (not
 * grouped, decided static) count in neither. Throws std::invalid_argument on different sizes. */
struct TIdentityCounts
{
	size_t true_objects = 0;  ///< distinct true objects with a moving reading
	size_t identities = 0;    ///< distinct estimated groups >= 0 among those readings
	size_t impure = 0;        ///< identities with readings of two or more true objects
	size_t split = 0;         ///< true objects whose readings fall into two or more identities
};
TIdentityCounts identityCounts(const std::vector<io::TReadingClass>& truth,
                               const std::vector<int64_t>& estimatedGroup);

/** Static landmarks of a final map that should not be there. */
struct TWrongStatic
{
	size_t map_size = 0;  ///< IDs given
	size_t wrong = 0;     ///< tracks with at least one moving or clutter reading
	size_t unknown = 0;   ///< IDs that no reading carries (not counted as wrong)
	std::vector<int32_t> wrong_ids;
};
/** mapIds: the written IDs of the static landmarks in the final map. */
TWrongStatic wrongStaticLandmarks(const std::vector<io::TReadingClass>& truth,
                                  const std::vector<int32_t>& mapIds);
}  // namespace dynslam::eval
