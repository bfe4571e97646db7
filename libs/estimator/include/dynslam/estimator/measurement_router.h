#pragma once
/** @file measurement_router.h
 * Seam 1 of the estimator core (doc/architecture.md): what each reading of a step is.
 * A router says, for every reading, static-known / static-new / object-first-sighting /
 * object-time-t / skip, and owns the object registry. One router serves the EKF and every
 * framework back-end. The first implementation, CIdRangeRouter, is the ID-range rule of
 * dynslam/core/landmark_ids.h (the oracle the paper assumes). */
#include <dynslam/core/models/measurement.h>
#include <dynslam/estimator/object_registry.h>
#include <dynslam/estimator/readings.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace dynslam::estimator
{
enum class Route : uint8_t
{
	StaticKnown,          ///< a static landmark in the state: updates it (Alg. 5)
	StaticNew,            ///< a static landmark not in the state: initialises it (Alg. 3)
	ObjectFirstSighting,  ///< a feature of an object whose time 0 is this step: its f_0
	ObjectTimeT,          ///< a known feature of an object first seen earlier: its f_t
	Skip                  ///< not used (counted in TRoutedStep)
};
const char* toString(Route r);

struct TRoutedReading
{
	TReading reading;
	Route route = Route::Skip;
	int32_t object = -1;   ///< object readings: the object
	int32_t feature = -1;  ///< object readings: the feature index within the object
	/** The reading of a track not yet classified (feature_labels = classify): a StaticNew
	 * candidate landmark (never an update of the ego) or a Skip. */
	bool candidate = false;
	/** Object readings (feature_labels = classify): the object identity, i.e. the object this
	 * reading's object continues after a track break (classify_link_gap; the first object of
	 * the chain), else `object`. The estimator's blocks are those of `object`. */
	int32_t identity = -1;
};

/** The routed readings of one step, in observation order, and what was skipped. */
struct TRoutedStep
{
	std::vector<TRoutedReading> readings;
	size_t skipped_unknown_object_feature = 0;  ///< object feature without an f_0
	size_t skipped_dropped_object = 0;          ///< reading of an object dropped from the state
	/** Readings with ID -1 skipped (no association: CIdRangeRouter without an association
	 * function or context; CClassifyingRouter without a static association). */
	size_t skipped_unknown_id = 0;
	/** feature_labels = boxes (box_router.h): corner readings of boxes whose track is not
	 * Confirmed (or that the tracker ignored), dropped before classification. */
	size_t skipped_box_corners = 0;
	/** ID -1 readings associated (unknown_id_association.h): with a static or candidate track,
	 * with a moving track, or started as a new track. */
	size_t unknown_id_static = 0, unknown_id_moving = 0, unknown_id_new = 0;
	size_t candidates = 0;  ///< readings of undecided tracks (not used by the filter)
	size_t held = 0;        ///< readings of static tracks held back as inconsistent (not used)
	/** Moving tracks decided static in this step (their object stopped, classify_stop_count):
	 * their reading starts a static landmark (StaticNew). */
	size_t stopped = 0;
	/** Tracks restarted as new candidates under a fresh ID: after a break, a reading
	 * inconsistent with the track's assignment (its ID reused by another point,
	 * classify_reuse_gap), or a moving track whose object the filter dropped
	 * (drop_object_after_unseen_steps): its readings start a new object once decided. */
	size_t restarted = 0;
	/** Moving tracks split off their object (classify_split_count): restarted as candidates. */
	size_t split = 0;
	/** Tracks decided moving that joined an object created in an earlier step (late joining:
	 * the filter gives them an f_0 from the object's pose). */
	size_t joined = 0;
	/** Hints (classify_use_hints, doc/results/classification.md "Hints"): readings whose hint
	 * differs from their track's first hint (the track keeps the first; the reading's is not used),
	 * and objects whose readings of this step carry two or more different hints (the grouping,
	 * decided by motion, is kept). */
	size_t hint_track_conflicts = 0, hint_group_conflicts = 0;
	/** New objects linked to an object lost before (classify_link: the same identity), and of
	 * those, the ones with two or more lost objects in the gate (the nearest was taken). */
	size_t linked = 0, link_ambiguous = 0;
	/** classify_merge_linked: links whose new object `from` (first seen in this step) the filter
	 * should merge into the lost object `into` (IMeasurementRouter::mergeObjects, after the
	 * step's commit; doc/results/classification.md "Merging a linked object"). */
	struct TMerge
	{
		int32_t from = -1, into = -1;
	};
	std::vector<TMerge> merges;
	/** Static landmarks decided moving in this step (a parked car drove off) with
	 * classify_reclassify = restart: the filter drops them from the state; their reading of this
	 * step is the first sighting of a new object. */
	std::vector<int32_t> reclassified;
	/** Static landmarks decided moving in this step with classify_reclassify = surgery: the
	 * filter turns each, in place, into f_0 of feature `feature` of object `object` (its mean
	 * and covariance, cross-covariances included, unchanged; doc/results/classification.md); the
	 * object is registered with its time 0 before this step, so their readings of this step
	 * are ObjectTimeT. */
	struct TConversion
	{
		int32_t id = -1, object = -1, feature = -1;
	};
	std::vector<TConversion> converted;
	/** Candidate landmarks to remove from the state (decided moving, or forgotten). */
	std::vector<int32_t> dropped_candidates;
	/** The readings with route r, in observation order. */
	std::vector<TRoutedReading> with(Route r) const;
	/** The readings of static landmarks (known and new), in observation order. */
	std::vector<TRoutedReading> statics() const;
	/** The object readings used this step (first sightings and time t), observation order. */
	std::vector<TRoutedReading> objects() const;
};

/** The readings of routed readings, in their order. */
std::vector<TReading> readingsOf(const std::vector<TRoutedReading>& r);

/** Routes object reading `m` (its object and feature set) by registering it in `registry`:
 * ObjectFirstSighting, ObjectTimeT, or Skip counted in out.skipped_unknown_object_feature (or,
 * for an object dropped from the state, out.skipped_dropped_object).
 * Shared by every router. */
void routeObjectReading(CObjectRegistry& registry, int step, TRoutedReading& m, TRoutedStep& out);

/** What a router that looks at the readings' geometry needs besides the readings (the
 * classifying router): the measurement model, its noise, the sensor pose and the step's
 * odometry increment u (robot frame) with its covariance U. */
/** The filter's own innovation of a reading of a static landmark (classify_static_test = map):
 * nu = z - h(ego predicted by this step's odometry, landmark), S = H P H^T + R over the joint
 * covariance of the predicted ego and the landmark, J_z_f = dh/d(landmark). */
struct TStaticInnovation
{
	Eigen::Vector2d nu = Eigen::Vector2d::Zero();
	Eigen::Matrix2d S = Eigen::Matrix2d::Identity();
	Eigen::Matrix2d J_z_f = Eigen::Matrix2d::Identity();
};

struct TRouterContext
{
	models::MeasurementModel model = models::MeasurementModel::Cartesian;
	Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
	Eigen::Vector3d sensor_pose = Eigen::Vector3d::Zero();
	Eigen::Vector3d u = Eigen::Vector3d::Zero();
	Eigen::Matrix3d U = Eigen::Matrix3d::Zero();
	/** Optional (set by the EKF): the innovation of reading z against landmark id of the state;
	 * false if id has no landmark there. */
	std::function<bool(int32_t id, const Eigen::Vector2d& z, TStaticInnovation& out)>
	    static_innovation;
	/** For routers that place detector boxes in the world (feature_labels = boxes,
	 * box_router.h): the step's boxes (null: none), the filter's ego pose at the start of the
	 * step (before this step's odometry u) and the step's time stamp [s] (NaN: none). */
	const std::vector<TBoxDetection>* boxes = nullptr;
	Eigen::Vector3d ego = Eigen::Vector3d::Zero();
	double stamp = std::numeric_limits<double>::quiet_NaN();
	/** Optional (the joint association, set by the EKF): the filter's predicted footprint
	 * centre (world) of the box track whose corner readings have IDs ids[0..3], with its
	 * covariance; false if the filter does not hold that track (yet). */
	std::function<bool(const std::array<int32_t, 4>& ids, Eigen::Vector2d& centre,
	                   Eigen::Matrix2d& cov)>
	    box_prediction;
};

struct TAssocTarget;  // unknown_id_association.h
class CBoxTracker;    // box_tracker.h
/** Static association of ID -1 readings: for every observed point the index of its
 * prediction, or -1 (unassociated). Points and predictions are in one 2-D space (the classifying
 * router: the robot frame; CIdRangeRouter: the measurement space); TAssocTarget in
 * unknown_id_association.h. */
using StaticAssociationFn = std::function<std::vector<int>(
    const std::vector<Eigen::Vector2d>& observed, const std::vector<TAssocTarget>& predictions)>;

class IMeasurementRouter
{
public:
	virtual ~IMeasurementRouter() = default;
	virtual std::string name() const = 0;
	/** Checks every reading of a step before the filter changes anything: throws
	 * std::runtime_error naming the reading, prefixed by `who`. */
	virtual void validate(const std::vector<TReading>& readings, const std::string& who) const = 0;
	/** The association of ID -1 readings with the static landmarks (ignored by routers that
	 * have none; without it, -1 readings are skipped and counted). */
	virtual void setStaticAssociation(StaticAssociationFn) {}
	/** The step's context, given before route() (ignored by routers that need none). */
	virtual void setContext(const TRouterContext&) {}
	/** Routes the readings of `step` (validated). isKnownStatic(id) says whether static
	 * landmark `id` is in the state. Registers new objects and first-sighting features. */
	virtual TRoutedStep route(int step, const std::vector<TReading>& readings,
	                          const std::function<bool(int32_t)>& isKnownStatic) = 0;
	virtual const CObjectRegistry& registry() const = 0;
	virtual CObjectRegistry& registry() = 0;
	/** The ID of feature `feature` of object `object` in this router's convention. */
	virtual int32_t featureId(int32_t object, int32_t feature) const = 0;
	virtual void reset() = 0;
	/** Object `from` continues as object `into` from the next step on (the filter has moved
	 * from's features into into's frame): the router routes from's features as into's. Routers
	 * that never list merges (TRoutedStep::merges) throw std::logic_error. */
	virtual void mergeObjects(int32_t from, int32_t into);
	/** Whether the router's evidence allows objects a and b to be one object (a live merge):
	 * true unless it knows better (CClassifyingRouter with use_hints: different boxes). */
	virtual bool allowsMerge(int32_t /*a*/, int32_t /*b*/) const { return true; }
	/** The box tracker of routers that track detector boxes (CBoxRouter), else null. */
	virtual const CBoxTracker* boxTracker() const { return nullptr; }
	/** Routers that track boxes: the robot pose the last step's boxes were placed with (the
	 * filter's ego predicted by the step's odometry); the tracker's tracks are relative to it. */
	virtual Eigen::Vector3d boxPlacementPose() const { return Eigen::Vector3d::Zero(); }
};

/** The ID-range rule (dynslam/core/landmark_ids.h): 0..99,999 static, 100,000 + 1000 object + k
 * feature k of object `object`. MRPT's "unknown landmark" ID -1 (INVALID_LANDMARK_ID) is
 * associated as CRangeBearingKFSLAM2D associates it: against the predictions of the static
 * landmarks in the state (TRouterContext::static_innovation) by a StaticAssociationFn (the EKF
 * installs MRPT's mrpt::slam::data_association_full_covariance with the classify_assoc_* keys,
 * MRPT's data_assoc_* names and defaults); a -1 reading associated with landmark `id` is that
 * landmark's reading (StaticKnown), an unassociated one starts a static landmark (StaticNew)
 * with a fresh ID kFirstResolvedId, kFirstResolvedId + 1, ... (MRPT: the map index). Unlike
 * MRPT, a landmark read with its own ID in the step is not a candidate (one reading per
 * landmark and step). Without an association function or a context (e.g. the framework
 * back-ends), -1 readings are skipped and counted (TRoutedStep::skipped_unknown_id). Any other
 * ID outside the ranges, and IDs from kFirstResolvedId on, are rejected by validate(). */
class CIdRangeRouter : public IMeasurementRouter
{
public:
	std::string name() const override { return "ids"; }
	void validate(const std::vector<TReading>& readings, const std::string& who) const override;
	void setContext(const TRouterContext& ctx) override { m_ctx = ctx, m_hasCtx = true; }
	void setStaticAssociation(StaticAssociationFn f) override { m_assoc = std::move(f); }
	TRoutedStep route(int step, const std::vector<TReading>& readings,
	                  const std::function<bool(int32_t)>& isKnownStatic) override;
	const CObjectRegistry& registry() const override { return m_registry; }
	CObjectRegistry& registry() override { return m_registry; }
	int32_t featureId(int32_t object, int32_t feature) const override;
	CIdRangeRouter() { reset(); }
	void reset() override;

private:
	/** Gives every -1 reading of `out` a route and an ID (or skips and counts it). */
	void resolveUnknown(TRoutedStep& out, const std::function<bool(int32_t)>& isKnownStatic);
	CObjectRegistry m_registry;
	StaticAssociationFn m_assoc;
	TRouterContext m_ctx;
	bool m_hasCtx = false;
	void addStatic(int32_t id);
	/** The static IDs routed StaticNew so far, sorted (the candidates of the -1 association;
	 * those no longer in the state are left out by isKnownStatic). */
	std::vector<int32_t> m_statics;
	int32_t m_next = 0;  ///< the next ID of a landmark started by a -1 reading (reset())
};

struct TClassifyParams;
/** The router of the INI option feature_labels: routers().make (seam_registries.h): "ids"
 * (CIdRangeRouter) or "classify" (CClassifyingRouter with `classify`, its defaults if null).
 * Throws std::invalid_argument. */
std::unique_ptr<IMeasurementRouter> makeRouter(const std::string& feature_labels,
                                               const TClassifyParams* classify = nullptr);
}  // namespace dynslam::estimator
