#pragma once
/** @file classifying_router.h
 * feature_labels = classify (issue 12, doc/results/classification.md): every non-negative reading
 * ID is an anonymous persistent track; the router decides static vs moving online and groups the
 * moving tracks into rigid objects, with no ID oracle.
 *
 * A new track is a candidate: not routed to the filter (Skip), so neither the ego nor the map
 * is touched while it is undecided. Its evidence is a small filter of the static hypothesis in
 * the robot frame: the point is carried through every odometry increment (TRouterContext::u,
 * U) and updated with each reading; each innovation nu (covariance S) adds the log-likelihood
 * ratio log N(nu; 0, S + sigma_m^2 I) - log N(nu; 0, S) of a moving point (a random walk of
 * sigma_m = motion_std per step) against a static one. Wald's sequential probability ratio
 * test decides: moving when the sum reaches log((1 - beta) / alpha), static when it falls to
 * log(beta / (1 - alpha)); after max_window sightings the sign of the sum decides.
 * With candidate_landmarks (default), a candidate's first reading initialises a landmark
 * (StaticNew: an augmentation, which does not change the ego) whose later readings are not used
 * until the track is decided: static -> StaticKnown updates (the first reading's information
 * is kept), moving -> the landmark is dropped (TRoutedStep::dropped_candidates), as is a
 * forgotten candidate. Without it, a decided static track starts with StaticNew. Moving -> a
 * feature of a new object, or of an object created in the same step whose features keep constant
 * distances to it (rigidDistanceTest, chi-square at group_prob, at most group_max_dist apart);
 * one-feature objects are allowed. A static track keeps its filter: a reading beyond the
 * reclassify_gate is held back (Skip, counted), reclassify_count consecutive ones turn it moving
 * (surgery, default: TRoutedStep::converted, the landmark becomes the f_0 of a new object whose
 * time 0 is its last consistent reading, grouped with the landmarks reclassified in the same
 * step; restart: TRoutedStep::reclassified, the filter drops the landmark and the reading becomes
 * the first sighting of a new object). ID -1 (association unknown): associated when a static
 * association function is set (setStaticAssociation; the EKF sets MRPT's), else skipped and
 * counted (TRoutedStep::skipped_unknown_id). With stop_count > 0, a moving track keeps a static
 * filter too (restarted at every reading beyond the reclassify_gate): stop_count consecutive
 * readings within the gate turn it static (its object stopped; TRoutedStep::stopped), and its
 * reading starts a static landmark. With use_hints, the readings' detection groups
 * (TReading::hint) keep different boxes apart and link a new object to a lost one of the same box;
 * link = All links without hints by a motion gate (classifying_router_links.cpp). */
#include <dynslam/estimator/classify_evidence.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/unknown_id_association.h>

#include <map>
#include <optional>
#include <set>

namespace dynslam::estimator
{
/** The INI keys classify_* of [DynamicKFSLAM] (dynslam/common/model_options.h). */
struct TClassifyParams
{
	double alpha = 0.01;              ///< classify_alpha: P(decide moving | static), in (0, 1)
	double beta = 0.01;               ///< classify_beta: P(decide static | moving), in (0, 1)
	double motion_std = 0.5;          ///< classify_motion_std [m per step], > 0
	int max_window = 10;              ///< classify_max_window: sightings before a forced decision
	int forget_steps = 20;            ///< classify_forget_steps: unseen candidates are forgotten
	double group_prob = 0.99;         ///< classify_group_prob: rigid-distance chi-square, (0, 1)
	double group_max_dist = 6;        ///< classify_group_max_dist [m]
	int reclassify_count = 3;         ///< classify_reclassify_count (0: never reclassify)
	double reclassify_gate = 0.999;   ///< classify_reclassify_gate: chi-square prob., (0, 1)
	bool candidate_landmarks = true;  ///< classify_candidate_landmarks (see the file comment)
	/** classify_reclassify: true (surgery, default): a reclassified static landmark becomes its
	 * object's f_0 in place (TRoutedStep::converted); false (restart): it is dropped and its
	 * reading starts a new object (TRoutedStep::reclassified). */
	bool surgery = true;
	/** classify_stop_count: a moving track becomes static after this many consecutive readings
	 * consistent with a static point (its object stopped; 0: never). */
	int stop_count = 0;
	/** classify_reuse_gap: a track unseen for at least this many steps whose reading is
	 * inconsistent with its assignment (a static track: beyond reclassify_gate; a moving one:
	 * with every other seen feature of its object) restarts as a new candidate under a fresh
	 * track ID (its ID was reused by another point; TRoutedStep::restarted; 0: never, the
	 * default: on real data it competes with the reclassification of slow movers held static,
	 * doc/results/classification.md). */
	int reuse_gap = 0;
	/** classify_split_count: consecutive readings of a moving track inconsistent with every
	 * other seen feature of its object that split it off: it restarts as a new candidate
	 * (TRoutedStep::split; the readings before are held back; 0: never). */
	int split_count = 3;
	/** classify_join: a track decided moving may join an object that exists already if its
	 * distances to that object's features stayed constant (TRoutedStep::joined). */
	bool join = true;
	/** classify_use_hints: the readings' detection groups (TReading::hint, a box ID) are
	 * evidence for grouping: a moving track never joins an object whose hint differs from its
	 * own, objects of its own hint are tried first, and a new object continues a lost object of
	 * its hint (classify_link_gap). A hint never overrides contradicting motion evidence. */
	bool use_hints = false;
	/** classify_link: which new objects may continue (identity, TRoutedReading::identity) an
	 * object lost after a track break: none (Off), only objects of the same hint (Hints, the
	 * default: with use_hints off no link is made), or also without hints, the nearest in the
	 * gate (All). See linkNewObjects and doc/results/classification.md. */
	enum class Link : uint8_t
	{
		Off,
		Hints,
		All
	};
	Link link = Link::Hints;
	/** classify_link_gap: the longest break [steps] between the lost object's last sighting and
	 * the new one's first that a link may span, >= 1. */
	int link_gap = 80;
	/** classify_merge_linked: a link also merges the new object into the lost one in the
	 * estimator (TRoutedStep::merges; the filter calls mergeObjects). The EKF sets it only with
	 * an object-centric model (cv, ctrv), which predicts the lost object across the gap
	 * (doc/results/classification.md "Merging a linked object"); false (default): identities only.
	 */
	bool merge_linked = false;
	/** classify_merge_live: two live objects that move as one rigid body (CLiveMergeDetector,
	 * live_merge.h) are merged in the estimator (the filter calls mergeObjects; off by default:
	 * doc/results/classification.md "Merging two live objects"). merge_live_window: increments per
	 * decision, >= 1, or 0 (default): 5 with cv / ctrv, 20 with the paper's model. */
	bool merge_live = false;
	int merge_live_window = 0;
	/** classify_static_test: how a static track's reading is tested before it updates the
	 * filter (reclassification). Robot (default): the robot-frame static filter carried by the
	 * odometry alone (TTrack::q). Map: if the track has a landmark in the filter's state, the
	 * filter's own innovation of the reading (TRouterContext::static_innovation: the ego
	 * predicted by this step's odometry and the landmark, with their joint covariance, so the
	 * heading the map corrects is corrected), else the robot-frame filter. */
	enum class StaticTest : uint8_t
	{
		Robot,
		Map
	};
	StaticTest static_test = StaticTest::Robot;
	TUnknownIdParams assoc;  ///< classify_assoc_*: ID -1 (unknown_id_association.h)
	/** Throws std::invalid_argument naming the key. */
	void validate() const;
};

enum class TrackClass : uint8_t
{
	Candidate,
	Static,
	Moving
};

/** What the router knows about one track. */
struct TTrack
{
	TrackClass cls = TrackClass::Candidate;
	TPoint2 q;             ///< static hypothesis: the point in the current robot frame
	bool q_valid = false;  ///< false: re-initialised at the next sighting
	double llr = 0;        ///< sum of the log-likelihood ratios (moving vs static)
	int sightings = 0, first_seen = -1, last_seen = -1, decided_step = -1;
	int bad_streak = 0;       ///< static: consecutive readings beyond the gate
	int still_streak = 0;     ///< moving: consecutive readings consistent with static
	int split_streak = 0;     ///< moving: consecutive readings inconsistent with its object
	int last_good = -1;       ///< static: step of its last reading within the gate
	bool converting = false;  ///< reclassified in this step with surgery (known landmark)
	int32_t object = -1, feature = -1;  ///< moving: its object and feature index
	int32_t hint = -1;                  ///< its first detection group (classify_use_hints)
	std::map<int, TPoint2> history;     ///< the last readings (robot frame), by step
};

class CClassifyingRouter : public IMeasurementRouter
{
public:
	explicit CClassifyingRouter(const TClassifyParams& p = TClassifyParams());
	std::string name() const override { return "classify"; }
	/** IDs >= 0 or -1; duplicates of an ID >= 0 in one step are rejected. */
	void validate(const std::vector<TReading>& readings, const std::string& who) const override;
	void setContext(const TRouterContext& ctx) override { m_ctx = ctx; }
	/** Throws std::logic_error if setContext was never called. */
	TRoutedStep route(int step, const std::vector<TReading>& readings,
	                  const std::function<bool(int32_t)>& isKnownStatic) override;
	const CObjectRegistry& registry() const override { return m_registry; }
	CObjectRegistry& registry() override { return m_registry; }
	/** The track ID of feature `feature` of object `object`. */
	int32_t featureId(int32_t object, int32_t feature) const override;
	void reset() override;
	/** Object `from` continues as object `into` (a merge listed in TRoutedStep::merges): its
	 * tracks become features of `into` (indices after its own), `from` leaves the registry.
	 * Throws std::logic_error if either is unknown or they are the same. */
	void mergeObjects(int32_t from, int32_t into) override;
	/** classify_merge_live with use_hints: false if objects a and b carry different hints
	 * (different boxes are different objects, as in grouping); true without hints. */
	bool allowsMerge(int32_t a, int32_t b) const override;

	const TClassifyParams& params() const { return m_p; }
	/** With a static association function, ID -1 readings are associated
	 * (unknown_id_association.h); without one they are skipped and counted. */
	void setStaticAssociation(StaticAssociationFn f) override
	{
		m_unknown.setStaticAssociation(std::move(f));
	}
	const std::map<int32_t, TTrack>& tracks() const { return m_tracks; }
	/** How many tracks the per-step prediction visits (m_live; bounded by the tracks read in
	 * the last forget_steps + 1 steps, whatever the length of the run). */
	size_t liveTrackCount() const { return m_live.size(); }
	/** How many tracks the -1 association carries (CUnknownIdResolver::moverCount). */
	size_t carriedTrackCount() const { return m_unknown.moverCount(); }
	double upperThreshold() const;  ///< log((1 - beta) / alpha): decide moving
	double lowerThreshold() const;  ///< log(beta / (1 - alpha)): decide static

private:
	/** Carries every live track through the step's odometry; forgets stale candidates. */
	void predictTracks(int step, TRoutedStep& out,
	                   const std::function<bool(int32_t)>& isKnownStatic);
	/** Whether track t has a static filter that predictTracks carries. */
	bool needsPrediction(const TTrack& t) const;
	/** A moving track's reading: true once stop_count consecutive readings were consistent with
	 * a static point (a static filter restarted at every inconsistent reading). */
	bool stoppedEvidence(TTrack& t, const TPoint2& z);
	/** Adds the evidence of one reading to a candidate; returns its decision (if any). */
	std::optional<TrackClass> addEvidence(TTrack& t, const TPoint2& z, int step);
	/** A static track's reading: true if consistent (and used by its filter). */
	bool checkStatic(int32_t id, TTrack& t, const TPoint2& z, int step);
	/** A static track decided moving now (inconsistent readings): grouped after the
	 * step's readings (turnedMoving); its landmark converted (surgery) or dropped. */
	void reclassifyStatic(int32_t id, TTrack& t, TRoutedStep& out,
	                      std::vector<int32_t>& turnedMoving,
	                      const std::function<bool(int32_t)>& isKnownStatic) const;
	/** classify_static_test = map: the filter's innovation of this step's reading of track id;
	 * false if not available (robot test, no landmark, no reading). */
	bool mapInnovation(int32_t id, TStaticInnovation& inn) const;
	/** Makes track id moving at step: joins an object created in this step, or one of an
	 * earlier step not in `exclude` (late joining, counted in out.joined), or starts one. */
	void makeMoving(int32_t id, TTrack& t, int step, std::vector<int32_t>& newObjects,
	                TRoutedStep& out, const std::vector<int32_t>& exclude);
	/** Registers the objects made of converted landmarks (surgery) and lists the conversions. */
	void registerConverted(const std::vector<int32_t>& objects, int step, TRoutedStep& out);
	static void remember(TTrack& t, const TPoint2& z, int step, int keep);
	enum class Act
	{
		Skip,
		Static,
		Moving
	};
	/** Updates track id with its reading z: what to do with it (moving tracks decided now are
	 * appended to turnedMoving and routed after grouping). */
	Act classifyOne(int32_t id, const TPoint2& z, int step, TRoutedStep& out, bool& candidate,
	                std::vector<int32_t>& turnedMoving,
	                const std::function<bool(int32_t)>& isKnownStatic);
	/** Gives every -1 reading of rd a track ID (unknown_id_association.h); pts: robot frame. */
	void resolveUnknownIds(int step, std::vector<TReading>& rd, const std::vector<TPoint2>& pts,
	                       TRoutedStep& out);
	/** Restarts of tracks inconsistent with their assignment (classify_reuse_gap, _split_count):
	 * renames rd's IDs of restarted tracks; fills held with moving readings held back. */
	void checkAssignments(int step, std::vector<TReading>& rd, const std::vector<TPoint2>& pts,
	                      const std::vector<int32_t>& external, TRoutedStep& out,
	                      std::set<int32_t>& held);
	/** Whether moving track id's reading z is inconsistent with every other seen feature of its
	 * object (now: the step's readings by track); false if none can be compared. */
	bool inconsistentWithObject(int32_t id, const TPoint2& z,
	                            const std::map<int32_t, TPoint2>& now) const;
	/** Track id is a moving feature of object obj (members of stopped tracks are stale). */
	bool isMember(int32_t id, int32_t obj) const;
	/** Gives the reading of track id a new track ID (a new candidate); returns it. */
	int32_t restartTrack(int32_t id, int32_t externalId);
	/** Late joining: an existing object (not in `exclude`) whose features keep constant distances
	 * to track t, or -1. */
	int32_t joinableObject(const TTrack& t, const std::vector<int32_t>& exclude) const;
	/** The rigid test of t against the live members of obj with at least 2 common steps; false
	 * if there is none. */
	bool rigidWithObject(const TTrack& t, int32_t obj) const;
	/** Hints: records the reading's hint on track t (conflicts counted in out). */
	void noteHint(TTrack& t, int32_t hint, TRoutedStep& out) const;
	/** Whether track t and object obj carry different hints (never grouped). */
	bool hintsDiffer(const TTrack& t, int32_t obj) const;
	/** The hint of object obj: the first hint of its members (-1: none). */
	int32_t objectHint(int32_t obj) const;
	/** Whether the step-wide motion predictions (m_unknown) are kept: -1 association or links. */
	bool predictsMotion() const { return m_unknown.active() || links(); }
	/** Whether links can be made (classify_link, classify_use_hints). */
	bool links() const
	{
		return m_p.link == TClassifyParams::Link::All ||
		       (m_p.link == TClassifyParams::Link::Hints && m_p.use_hints);
	}
	/** A new object's centroid c and mean velocity v (robot frame, this step; now: the step's
	 * readings by track) and its first sighting; false if none of its features has both. */
	bool newObjectMotion(int32_t obj, int step, const std::map<int32_t, TPoint2>& now,
	                     Eigen::Vector2d& c, Eigen::Vector2d& v, int& first) const;
	/** Links each object created in this step to a lost object (classify_link_gap). */
	void linkNewObjects(int step, const std::vector<int32_t>& newObjects,
	                    const std::map<int32_t, TPoint2>& now, TRoutedStep& out);
	/** Counts the objects whose readings of this step carry different hints. */
	void countGroupHintConflicts(TRoutedStep& out) const;
	/** An object reading of moving track t through the registry. */
	void routeMoving(TRoutedReading& m, const TTrack& t, int step, TRoutedStep& out);

	TClassifyParams m_p;
	std::optional<TRouterContext> m_ctx;
	std::map<int32_t, TTrack> m_tracks;
	/** The tracks predictTracks has work for (bounded bookkeeping, issue 29): a superset of
	 * those with a valid static filter that is carried (not moving, or moving with stop_count);
	 * a track enters when it is read, leaves at the first step it has nothing to do. The others
	 * (static tracks out of view, moving tracks) cost nothing per step. */
	std::set<int32_t> m_live;
	CObjectRegistry m_registry;
	std::map<int32_t, std::vector<int32_t>> m_objectTracks;  ///< object -> track IDs
	int32_t m_nextObject = 0;
	std::map<int32_t, int32_t> m_alias;     ///< input track ID -> its track after restarts
	std::map<int32_t, int32_t> m_identity;  ///< object -> the object it continues (links)
	std::set<int32_t> m_continued;          ///< objects already continued by a newer one
	int m_lastStep = -1;
	CUnknownIdResolver m_unknown;
	std::map<int32_t, Eigen::Vector2d> m_rawNow;  ///< this step's readings (model space) by track
};
}  // namespace dynslam::estimator
