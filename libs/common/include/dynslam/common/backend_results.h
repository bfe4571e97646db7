#pragma once
/** @file backend_results.h
 * The result getters every back-end shares: object tracks from the object registry (first
 * sighting, feature set, the poses recorded when dropped), completed by the back-end with the
 * poses still in its state and sorted. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/estimator/object_registry.h>

#include <map>

namespace dynslam
{
/** One track per registered object: object, first_step, num_features and the dropped poses. */
std::map<int32_t, TObjectTrack> tracksFromRegistry(const estimator::CObjectRegistry& reg);
/** Sorts every track's poses by step (stable: dropped ones before in-state ones of a step). */
void sortTrackPoses(std::map<int32_t, TObjectTrack>& tracks);
/** A dropped pose as a result. */
TObjectPoseEstimate toEstimate(const estimator::TPoseRecord& r);
/** A pose as a dropped-pose record (dim 2 or 3). */
estimator::TPoseRecord toRecord(const TObjectPoseEstimate& e);
/** The velocity of a pose as a record (2 or 3 entries; throws std::invalid_argument otherwise).
 * tracksFromRegistry attaches it to the dropped pose of the same step. */
estimator::TVelocityRecord toVelocityRecord(const TObjectPoseEstimate& e);
}  // namespace dynslam
