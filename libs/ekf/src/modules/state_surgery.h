#pragma once
/** @file state_surgery.h
 * (Internal to dynslam::ekf.) The state surgeries of classification (feature_labels = classify,
 * doc/results/classification.md), on the filter's working state through TFilterAccess:
 *  - convertStaticLandmarks: the step's, right after routing (a parked car drove off);
 *  - mergeObjects: the merge modules' (linked_merge.h, live_merge.h).
 * CDynamicKFSLAM2D's protected members of the same names delegate here (the tests call them). */
#include <cstdint>
#include <vector>

#include "filter_module.h"

namespace dynslam::ekf
{
/** Each static landmark c.id becomes, in place, f_0 of feature c.feature of object c.object (the
 * router has registered the objects); the mean and the covariance (cross-covariances included)
 * are unchanged, only the block's label changes. Throws std::logic_error, changing nothing, if
 * an ID is not a static landmark in the state or is listed twice. Counted in
 * TStepReport::converted_static. */
void convertStaticLandmarks(TFilterAccess& a,
                            const std::vector<estimator::TRoutedStep::TConversion>& c);

/** Merge (classify_merge_linked, doc/results/classification.md "Merging a linked object"; and
 * classify_merge_live): the features of object `from` are re-expressed in the body frame of
 * object `into` (models/object_merge.h; x' = g(x), P' = J P J^T by estimator::state::replace),
 * from's poses, velocity and time-t features leave the state, and the router routes from's
 * tracks as into's. False (nothing changed) if `into` has no velocity and pose (not predicted
 * across the gap), or, with the paper's model (classify_merge_live), if either has no pose of
 * this step. Throws std::logic_error if an object is unknown or they are the same. */
bool mergeObjects(TFilterAccess& a, int32_t from, int32_t into);
}  // namespace dynslam::ekf
