#pragma once
/** @file drop_policy.h
 * The one drop policy of every back-end (the paper: "poses and features present in the
 * optimization window may be dropped"; design.md): time-t object features once they served
 * the pose, object poses beyond the last K, and static landmarks unseen for N steps. The
 * back-ends ask it what to drop; how they drop (remove rows and columns of a covariance, or
 * marginalize a running cost) is theirs. */
#include <cstddef>
#include <cstdint>
#include <map>

namespace dynslam::estimator
{
struct TDropOptions
{
	bool drop_time_t_features = true;
	int keep_last_poses = 1;                 ///< K >= 1
	int drop_static_after_unseen_steps = 0;  ///< N; 0 = never
	bool record_dropped = true;              ///< keep the last estimate of what is dropped
	/** Pruning (clutter): a static landmark read in fewer than prune_min_sightings (k) of the
	 * prune_window (W) steps that start with its first reading is dropped at the end of the
	 * window's last step; 0 = off. */
	int prune_min_sightings = 0;
	int prune_window = 0;
	/** An object with no used reading (first sighting or time t) for this many steps is
	 * dropped: all its blocks leave the state, its track is recorded per record_dropped;
	 * 0 = never. */
	int drop_object_after_unseen_steps = 0;
};

class CDropPolicy
{
public:
	CDropPolicy() = default;
	explicit CDropPolicy(const TDropOptions& o) : m_opts(o) {}
	const TDropOptions& options() const { return m_opts; }
	void clear()
	{
		m_seen.clear();
		m_objectSeen.clear();
	}
	/** Static landmark `id` was read at `step` (at most once per step): its last reading and,
	 * while its pruning window is open, its count of readings. */
	void noteSeen(int32_t id, int step);
	/** Static landmark `id` left the state: no longer tracked (read again, it starts anew). */
	void forget(int32_t id) { m_seen.erase(id); }
	/** The step static landmark `id` was last read at, `fallback` if never noted. */
	int lastSeen(int32_t id, int fallback) const
	{
		const auto it = m_seen.find(id);
		return it == m_seen.end() ? fallback : it->second.last;
	}
	/** Whether static landmark `id` is due to be dropped at the end of `step`: last read at
	 * least N steps ago (N > 0). `addedStep` stands in for a landmark never noted. */
	bool staticDue(int32_t id, int step, int addedStep) const;
	/** Pruning (k = prune_min_sightings > 0, W = prune_window): whether static landmark `id`
	 * is due to be pruned at the end of `step`: its window (the W steps from its first reading
	 * on; from `addedStep` for a landmark never noted) ends at or before `step` and it was read
	 * in fewer than k of them. */
	bool pruneDue(int32_t id, int step, int addedStep) const;
	/** Either rule: dropped (unseen) or pruned. */
	bool due(int32_t id, int step, int addedStep) const
	{
		return staticDue(id, step, addedStep) || pruneDue(id, step, addedStep);
	}
	/** Object `obj` had a used reading at `step`. */
	void noteObjectSeen(int32_t obj, int step) { m_objectSeen[obj] = step; }
	/** Object `obj` left the state: no longer tracked. */
	void forgetObject(int32_t obj) { m_objectSeen.erase(obj); }
	/** Whether object `obj` is due to be dropped at the end of `step`: its last used reading
	 * at least N = drop_object_after_unseen_steps steps ago (N > 0); `firstStep` stands in for
	 * an object never noted. */
	bool objectDue(int32_t obj, int step, int firstStep) const;
	/** How many of an object's `numPoses` poses (oldest first) to drop: those beyond K. */
	size_t posesToDrop(size_t numPoses) const;
	bool dropTimeT() const { return m_opts.drop_time_t_features; }
	bool record() const { return m_opts.record_dropped; }

private:
	TDropOptions m_opts;
	struct TSeen
	{
		int last = -1;   ///< the last step it was read at
		int first = -1;  ///< the step of its first reading (its pruning window starts there)
		int count = 0;   ///< readings inside its pruning window (pruning on only)
	};
	std::map<int32_t, TSeen> m_seen;      ///< the static landmarks in the state that were read
	std::map<int32_t, int> m_objectSeen;  ///< object -> the last step with a used reading
};
}  // namespace dynslam::estimator
