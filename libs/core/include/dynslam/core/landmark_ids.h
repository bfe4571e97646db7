#pragma once
/** @file landmark_ids.h
 * The one place that defines how a landmark ID in a CObservationBearingRange tells a
 * static landmark from a feature of a moving object.
 *
 * | range                          | meaning                                             |
 * |--------------------------------|-----------------------------------------------------|
 * | 0 .. 99'999                    | static landmark, ID = landmark number               |
 * | 100'000 + 1000*obj + k         | feature k (0..999) of moving object obj (0..kMaxObject) |
 * | negative (e.g. -1, MRPT's INVALID_LANDMARK_ID), or above the last object | invalid: rejected |
 *
 * Both filters (the static CRangeBearingKFSLAM2D and the dynamic one) read the same IDs,
 * so the static baseline sees every moving feature as just another landmark. */
#include <cstdint>
#include <string>

namespace dynslam::ids
{
constexpr int32_t kStaticMin = 0;
constexpr int32_t kStaticMax = 99'999;
constexpr int32_t kObjectBase = 100'000;
constexpr int32_t kFeaturesPerObject = 1000;
constexpr int32_t kMaxObject = (INT32_MAX - kObjectBase) / kFeaturesPerObject - 1;

enum class IdKind
{
	Static,
	ObjectFeature,
	Invalid
};

constexpr IdKind classify(int32_t id)
{
	if (id >= kStaticMin && id <= kStaticMax) return IdKind::Static;
	if (id >= kObjectBase && (id - kObjectBase) / kFeaturesPerObject <= kMaxObject)
		return IdKind::ObjectFeature;
	return IdKind::Invalid;
}
constexpr bool isStatic(int32_t id) { return classify(id) == IdKind::Static; }
constexpr bool isObjectFeature(int32_t id) { return classify(id) == IdKind::ObjectFeature; }
/** Object index of an object-feature ID (precondition: isObjectFeature(id)). */
constexpr int32_t objectOf(int32_t id) { return (id - kObjectBase) / kFeaturesPerObject; }
/** Feature index within its object (precondition: isObjectFeature(id)). */
constexpr int32_t featureOf(int32_t id) { return (id - kObjectBase) % kFeaturesPerObject; }
/** ID of feature k of object obj. Throws std::out_of_range on bad indices. */
int32_t objectFeatureId(int32_t obj, int32_t k);
/** Human-readable description, e.g. "static landmark 12" or "object 1 feature 3". */
std::string describe(int32_t id);
}  // namespace dynslam::ids
