#pragma once
/** @file reader.h
 * (Internal to dynslam::ekf.) The results of CDynamicKFSLAM2D, read from the whole state (layout,
 * mean, covariance) and the gauge's output term through the const view TFilterView: the facade's
 * getters are one-line calls of these. By concern: landmarks.cpp (static landmarks, live and
 * dropped; object features), object_tracks.cpp (pose histories; live objects), world_poses.cpp
 * (an object's pose in the world), state_dump.cpp (the state without pads, its labels, the
 * reported covariance), slot_view.cpp (the layout as MRPT's 2-dof slots). Every marginal
 * includes the prior gauge's output term (gauge/prior_gauge.h; zero with prior_gauge = prior). */
#include <mrpt/poses/CPosePDFGaussian.h>

#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "../modules/filter_module.h"

namespace dynslam::ekf::results
{
// landmarks.cpp
/** The ego pose of the working state. */
mrpt::poses::CPosePDFGaussian egoPose(const TFilterView& v);
/** The live map: the static landmarks of the whole state. */
std::vector<TStaticLandmarkEstimate> staticLandmarks(const TFilterView& v);
/** The static landmarks dropped from the state (drop_static_after), their last estimates. */
std::vector<TStaticLandmarkEstimate> droppedStaticLandmarks(const TFilterView& v);
/** Object features in the state (time 0 and, if kept, time t), then the recorded f_0 of objects
 * dropped by drop_object_after_unseen_steps (with record_dropped). */
std::vector<TObjectFeatureEstimate> objectFeatures(const TFilterView& v);

// object_tracks.cpp
/** Every object's pose history: dropped poses (recorded) and poses in the state. A pose is
 * xi = (dx, dy, dtheta), the motion since the object's first sighting: a rotation by dtheta
 * about c0, the centroid of its features seen then (its founders' f_0), then the translation
 * (dx, dy); (dx, dy) for a one-feature object (models/object_pose.h). The newest pose of an
 * object with a velocity block carries the velocity. Without mode probabilities (the facade
 * attaches those, object_model = mm). */
std::map<int32_t, TObjectTrack> objectTracks(const TFilterView& v);
/** The objects with at least one block in the working state (no expanded copy). */
size_t liveObjectCount(const TFilterView& v);

// world_poses.cpp
/** The object's pose in the world (object_world_estimate.h, models/object_world_pose.h) at its
 * newest pose in the state, for every object_model, with the facade's getObjectVelocity; empty
 * if its newest pose is no longer in the state or a founder's f_0 is missing. Throws
 * std::invalid_argument for an object the filter does not know. */
std::optional<TObjectWorldPose> objectWorldPose(const TFilterView& v, int32_t object);
/** objectWorldPose of every known object that has one. */
std::map<int32_t, TObjectWorldPose> objectWorldPoses(const TFilterView& v);

// state_dump.cpp
/** Mean and reported covariance of the whole state without pad entries; labels[i] names entry i
 * (e.g. "ego.x", "lm3.y", "obj1.f2.t0.x", "obj1.xi4.dtheta", "odo.b_w"). */
void stateWithoutPads(const TFilterView& v, Eigen::VectorXd& x, Eigen::MatrixXd& P,
                      std::vector<std::string>* labels);
/** The whole state's pad entries. */
std::vector<size_t> padIndices(const TFilterView& v);
/** N = d(state)/d(delta) of the whole state (CPriorGauge::jacobian). */
Eigen::MatrixXd gaugeJacobian(const TFilterView& v);
/** The whole state's covariance reported outward (CPriorGauge::reported). */
Eigen::MatrixXd reportedCov(const TFilterView& v);

// slot_view.cpp
/** The slot view of `layout` (a 3-dof pose is ObjectPoseA + ObjectPoseB) and, if given, its
 * (landmark ID, block) pairs. */
void slotsOf(const estimator::CPaddedLayout& layout, std::vector<TSlot>& slots,
             std::vector<std::pair<int32_t, size_t>>* statics);
/** map = {id -> block} of the (id, block) pairs (the last block of an ID listed twice), updated
 * in place: the nodes of the IDs it keeps are reused (a step's commit used to clear and rebuild
 * the whole map, one allocation per static landmark). */
void assignInPlace(std::map<int32_t, size_t>& map, std::vector<std::pair<int32_t, size_t>>& pairs);
}  // namespace dynslam::ekf::results
