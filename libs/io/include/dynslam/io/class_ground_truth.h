#pragma once
/** @file class_ground_truth.h
 * Ground truth of the class of every reading (issue 12: online static / moving
 * classification), independent of MRPT. Written by dynslam-simulate beside the other
 * ground-truth files as D/B_gt_classes.csv, one row per reading of each observation, in the
 * order of the observation:
 *
 *     step,t,index,id,true_id,class,object,feature
 *
 *  - step, t: the step k and its time stamp (the same t as B_gt_ego.csv);
 *  - index: position of the reading in the step's CObservationBearingRange (0-based);
 *  - id: the ID written in the rawlog (anonymous, after a track break, a clutter ID or -1);
 *  - true_id: the ID under the landmark_ids.h convention (landmark ID, or
 *    100000 + 1000 object + feature), -1 for clutter;
 *  - class: static | moving | clutter (a parked object's features are static while it
 *    stands still, moving while it moves);
 *  - object: the true object index (also while parked), -1 for static landmarks and clutter;
 *  - feature: the landmark ID for static landmarks, the feature index within its object for
 *    object features, -1 for clutter.
 * The reader rejects malformed files naming file and line. */
#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::io
{
enum class TrueClass : uint8_t
{
	Static,
	Moving,
	Clutter
};
/** "static", "moving", "clutter". */
const char* toString(TrueClass c);

struct TReadingClass
{
	int step = 0;
	double t = 0;
	int index = 0;
	int32_t id = -1;
	int32_t true_id = -1;
	TrueClass cls = TrueClass::Static;
	int32_t object = -1;
	int32_t feature = -1;
	bool operator==(const TReadingClass& o) const
	{
		return step == o.step && t == o.t && index == o.index && id == o.id &&
		       true_id == o.true_id && cls == o.cls && object == o.object && feature == o.feature;
	}
};

/** Writes rows (any order is kept) to path with the header above; numbers of t as the other
 * ground-truth CSVs (shortest exact representation). Throws std::runtime_error on I/O. */
void writeClassGroundTruth(const std::vector<TReadingClass>& rows, const std::string& path);
/** Reads the file back exactly. Throws std::runtime_error naming file and line on a missing
 * file, a wrong header, a malformed number, an unknown class or inconsistent fields (a static
 * row with an object, a clutter row with a true ID, a moving row without an object). */
std::vector<TReadingClass> readClassGroundTruth(const std::string& path);
}  // namespace dynslam::io
