#pragma once
/** @file unknown_id_association.h
 * Readings with ID -1 (MRPT's "association unknown") under feature_labels = classify (issue 12,
 * item 4; doc/results/classification.md, "Unknown IDs"). Before the classifying router classifies a
 * step, every -1 reading gets a track ID:
 *  1. static: associated with the static and candidate tracks by a StaticAssociationFn (the EKF
 *     installs MRPT's mrpt::slam::data_association_full_covariance with the classify_assoc_*
 *     options, as CRangeBearingKFSLAM2D does); the predictions are the router's static-hypothesis
 *     filters of the tracks (robot frame), their covariance plus the reading noise at the
 *     predicted point;
 *  2. moving: the rest, by nearest-neighbour gating (chi-square 2 dof at
 *     classify_assoc_moving_gate, one reading per track, smallest distance first) against the
 *     predicted points of the moving and candidate tracks seen at least twice: each track's last
 *     reading carried through the odometry increments with the displacement per step of its
 *     last two readings (constant velocity in the world), covariance the reading's plus
 *     classify_motion_std^2 per step;
 *  3. second sighting: the rest, nearest first, against the candidate tracks seen once (no
 *     velocity yet) within classify_assoc_max_step metres per step of their carried reading
 *     (the largest displacement of a moving point per step; 0: off);
 *  4. otherwise: a new anonymous track, ID kFirstResolvedId, kFirstResolvedId + 1, ...
 * A track that already has a reading with an explicit ID in the step is not a candidate.
 * Pure Eigen (no MRPT): the static association is injected. */
#include <dynslam/estimator/classify_evidence.h>

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dynslam::estimator
{
/** The classify_assoc_* keys of [DynamicKFSLAM] (names and values as MRPT's
 * CRangeBearingKFSLAM2D data_assoc_* options). */
struct TUnknownIdParams
{
	std::string method = "assocNN";        ///< classify_assoc_method: assocNN | assocJCBB
	std::string metric = "metricMaha";     ///< classify_assoc_metric: metricMaha | metricML
	double IC_chi2_thres = 0.99;           ///< classify_assoc_IC_chi2_thres, in (0, 1)
	std::string IC_metric = "metricMaha";  ///< classify_assoc_IC_metric: metricMaha | metricML
	double IC_ml_threshold = 0.0;          ///< classify_assoc_IC_ml_threshold
	double moving_gate = 0.99;             ///< classify_assoc_moving_gate, in (0, 1)
	double max_step = 0;  ///< classify_assoc_max_step [m per step], >= 0 (0: no second sightings)
	/** Throws std::invalid_argument naming the key. */
	void validate() const;
};

/** IDs given to the tracks started by -1 readings; input IDs from here on are rejected. */
constexpr int32_t kFirstResolvedId = 1'000'000'000;

/** A track a -1 reading may belong to: its ID and predicted point (robot frame; covariance
 * including the reading noise at that point). */
struct TAssocTarget
{
	int32_t id = -1;
	TPoint2 pred;
};

// StaticAssociationFn (the static association of -1 readings): measurement_router.h.

/** What became of the -1 readings of one step. */
struct TResolvedIds
{
	std::vector<int32_t> ids;  ///< per reading: its ID (the input one, or the resolved one)
	size_t to_static = 0, to_moving = 0, to_second = 0, new_tracks = 0;
};

/** The resolver's prediction of one track (its last reading carried to the current step). */
struct TTrackPrediction
{
	TAssocTarget target;                            ///< covariance without the reading noise
	bool has_vel = false;                           ///< seen twice: constant-velocity prediction
	int gap = 1;                                    ///< steps since the last reading
	Eigen::Vector2d vel = Eigen::Vector2d::Zero();  ///< displacement per step (current frame)
};

class CUnknownIdResolver
{
public:
	explicit CUnknownIdResolver(const TUnknownIdParams& p = TUnknownIdParams());
	void setStaticAssociation(StaticAssociationFn f) { m_static = std::move(f); }
	/** -1 readings are resolved only with a static association function (without one the
	 * router skips and counts them). */
	bool active() const { return bool(m_static); }
	/** Carries every track's last reading and velocity through one odometry increment (once
	 * per step, before resolve). Lazily: the increment is recorded, and a track is carried
	 * through the increments it missed when it is read (observe, velocityWith, predictions);
	 * each track gets the same operations in the same order as an eager carry, so the results
	 * are bit-identical, while the tracks not seen for a while cost nothing per step. The
	 * increments are kept until every track has had them (looked for when their number has
	 * doubled): memory of one increment per step while a track read long ago is never read
	 * again, no per-step cost (issue 29: carrying every track every 256 steps cost the number
	 * of tracks ever read, per step). */
	void predict(const Eigen::Vector3d& u, const Eigen::Matrix3d& U);
	/** The predicted points of all tracks at `step` (covariance + motion_std^2 per step). */
	std::vector<TTrackPrediction> predictions(int step, double motion_std) const;
	/** The prediction of track id alone (as in predictions), none if it has no reading. */
	std::optional<TTrackPrediction> prediction(int32_t id, int step, double motion_std) const;
	/** Resolves the -1 entries of ids (points z: the readings in the robot frame): statics by
	 * the static association, moving (constant-velocity predictions, with the reading noise) by
	 * the gate, then once (candidates seen once, covariance unused) within max_step * gap. */
	TResolvedIds resolve(const std::vector<int32_t>& ids, const std::vector<TPoint2>& z,
	                     const std::vector<TAssocTarget>& statics,
	                     const std::vector<TAssocTarget>& moving,
	                     const std::vector<TTrackPrediction>& once = {});
	/** A reading of a track (every reading with an ID, after resolve). */
	void observe(int32_t id, const TPoint2& z, int step);
	void forget(int32_t id) { m_movers.erase(id); }
	/** The tracks carried (every track read and not forgotten). */
	size_t moverCount() const { return m_movers.size(); }
	/** The displacement per step (current robot frame) that observe(id, z, step) would set;
	 * false if track id has no earlier reading. */
	bool velocityWith(int32_t id, const TPoint2& z, int step, Eigen::Vector2d& vel) const;
	/** A fresh track ID from the counter of the -1 tracks (a restarted track,
	 * classifying_router.h). */
	int32_t newId() { return m_next++; }
	/** Forgets the moving tracks and restarts the ID counter (keeps the association function). */
	void reset();
	const TUnknownIdParams& params() const { return m_p; }

private:
	struct TMover
	{
		TPoint2 last;  ///< the last reading, carried to the current robot frame
		Eigen::Vector2d vel = Eigen::Vector2d::Zero();  ///< displacement per step (robot frame)
		int last_step = -1;
		bool has_vel = false;
		size_t carried = 0;  ///< odometry increments applied (the count of predict calls)
	};
	/** Carries m through the increments it has not had yet. */
	void carry(TMover& m) const;
	TTrackPrediction predictionOf(int32_t id, TMover& m, int step, double motion_std) const;
	TUnknownIdParams m_p;
	StaticAssociationFn m_static;
	mutable std::map<int32_t, TMover> m_movers;  ///< carried lazily (predict)
	std::vector<TStaticMotion> m_increments;     ///< the increments from number m_firstIncrement on
	size_t m_firstIncrement = 0, m_predicts = 0;
	size_t m_compactAt = 256;  ///< the list's length at which predict looks for what to forget
	int32_t m_next = kFirstResolvedId;
};
}  // namespace dynslam::estimator
