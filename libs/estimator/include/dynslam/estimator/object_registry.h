#pragma once
/** @file object_registry.h
 * The one object registry of every back-end: for each moving object, the step of its first
 * sighting (its time 0) and its feature set (the features seen then, in observation order),
 * and the poses recorded when they were dropped from the state. A feature is "time 0" in the
 * step of the first sighting, "time t" afterwards if it belongs to the feature set, and
 * unknown otherwise (it has no f_0: skipped and counted, doc/state-layout.md). */
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

namespace dynslam::estimator
{
/** A dropped object pose, stored without heap members: millions of them in a long run must not
 * interleave small allocations with the step's temporaries (heap fragmentation). */
struct TPoseRecord
{
	int step = -1, dim = 0;  ///< dim 3 (dx, dy, dtheta) or 2 (dx, dy)
	Eigen::Vector3d mean = Eigen::Vector3d::Zero();
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

/** The velocity of a dropped pose's step (object_model = cv | ctrv: the world-frame velocity of
 * the reference point and the turn rate, models/object_motion.h). Kept apart from TPoseRecord
 * so the paper's models, which have none, do not pay for it in long runs. */
struct TVelocityRecord
{
	int step = -1, dim = 0;  ///< dim = the pose's dim
	Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

struct TObjectEntry
{
	int first_step = -1;
	std::vector<int32_t> feature_ids;        ///< features seen at time 0, in observation order
	std::vector<int32_t> feature_index;      ///< their feature index within the object
	std::vector<TPoseRecord> dropped_poses;  ///< ascending step
	std::vector<TVelocityRecord> dropped_velocities;  ///< ascending step (velocity models only)
	/** The features seen at time 0 (the first `founders` of feature_ids): they define the pose's
	 * centroid c0 and its dimension. Features that joined later (addFeature) follow them. */
	int founders = 0;
	/** Readings of features not in the feature set (FeatureRole::Unknown: first seen after the
	 * object's first sighting and not joined; skipped), and their distinct IDs, ascending. */
	size_t skipped_late_readings = 0;
	std::vector<int32_t> skipped_late_ids;
	/** Dropped from the state (drop_object_after_unseen_steps): its later readings are skipped
	 * (FeatureRole::Dropped); its recorded poses stay. */
	bool dropped = false;
	/** Index of feature `id` in feature_ids, or -1 if it is not in the feature set. */
	int indexOf(int32_t id) const;
	/** 1 founder: translation-only pose (2 entries); otherwise (dx, dy, dtheta). */
	int poseDim() const { return founders == 1 ? 2 : 3; }
};

/** How a reading of an object feature relates to the registry (see the file comment). */
enum class FeatureRole
{
	FirstSighting,  ///< the object's time 0 is this step: the reading defines f_0
	TimeT,          ///< a known feature of an object first seen earlier: f_t
	Unknown,        ///< not in the object's feature set: no f_0, skipped
	Dropped         ///< the object was dropped from the state: skipped
};

class CObjectRegistry
{
public:
	void clear() { m_objects.clear(); }
	/** Registers the reading of feature `id` (index `feature` within the object) of object
	 * `obj` at `step` and says its role. A first sighting adds it to the object's feature set. */
	FeatureRole registerReading(int32_t obj, int32_t id, int32_t feature, int step);
	/** Registers object `obj` with its whole feature set at once and time 0 `first_step` (state
	 * surgery: static landmarks that became its f_0, doc/results/classification.md). Its readings
	 * are time t from the step after first_step on. Throws std::logic_error if obj exists, if ids
	 * is empty or if ids and index differ in size. */
	void registerObject(int32_t obj, int first_step, const std::vector<int32_t>& ids,
	                    const std::vector<int32_t>& index);
	/** Late joining (doc/results/classification.md): feature `id` (index `feature`) joins object
	 * `obj` after its time 0; its readings are time t from now on (the filter gives it an f_0 from
	 * its first one). Throws std::logic_error if obj does not exist or already has id. */
	void addFeature(int32_t obj, int32_t id, int32_t feature);
	/** Object obj was dropped from the state (TObjectEntry::dropped). Throws std::logic_error if
	 * it does not exist. */
	void markDropped(int32_t obj);
	/** Removes object obj (merged into another, classify_merge_linked). */
	void erase(int32_t obj) { m_objects.erase(obj); }
	bool has(int32_t obj) const { return m_objects.count(obj) != 0; }
	const TObjectEntry& at(int32_t obj) const { return m_objects.at(obj); }
	TObjectEntry& at(int32_t obj) { return m_objects.at(obj); }
	const std::map<int32_t, TObjectEntry>& objects() const { return m_objects; }
	/** Records a dropped pose (ignored if `record` is false: memory stays bounded). */
	void recordDroppedPose(int32_t obj, const TPoseRecord& r, bool record);
	/** The velocity of a dropped pose (recorded with it, same step). */
	void recordDroppedVelocity(int32_t obj, const TVelocityRecord& r, bool record);
	/** True if `step` is a time-t step of object obj (the object exists and was first seen
	 * earlier). */
	bool isTimeT(int32_t obj, int step) const;

private:
	std::map<int32_t, TObjectEntry> m_objects;
};
}  // namespace dynslam::estimator
