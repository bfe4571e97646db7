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
};

class CDropPolicy
{
public:
	CDropPolicy() = default;
	explicit CDropPolicy(const TDropOptions& o) : m_opts(o) {}
	const TDropOptions& options() const { return m_opts; }
	void clear() { m_lastSeen.clear(); }
	/** Static landmark `id` was read at `step`. */
	void noteSeen(int32_t id, int step) { m_lastSeen[id] = step; }
	/** Static landmark `id` left the state: no longer tracked. */
	void forget(int32_t id) { m_lastSeen.erase(id); }
	/** The step static landmark `id` was last read at, `fallback` if never noted. */
	int lastSeen(int32_t id, int fallback) const
	{
		const auto it = m_lastSeen.find(id);
		return it == m_lastSeen.end() ? fallback : it->second;
	}
	/** Whether static landmark `id` is due to be dropped at the end of `step`: last read at
	 * least N steps ago (N > 0). `addedStep` stands in for a landmark never noted. */
	bool staticDue(int32_t id, int step, int addedStep) const;
	/** How many of an object's `numPoses` poses (oldest first) to drop: those beyond K. */
	size_t posesToDrop(size_t numPoses) const;
	bool dropTimeT() const { return m_opts.drop_time_t_features; }
	bool record() const { return m_opts.record_dropped; }

private:
	TDropOptions m_opts;
	std::map<int32_t, int> m_lastSeen;
};
}  // namespace dynslam::estimator
