/** CClassifyingRouter: the input IDs (validate), tracks whose readings contradict their
 * assignment (an ID reused after a break, a feature that leaves its object) and late joining
 * (doc/results/classification.md, "Grouping"). */
#include <dynslam/estimator/classifying_router.h>

#include <Eigen/LU>
#include <algorithm>
#include <set>
#include <stdexcept>

namespace dynslam::estimator
{
namespace
{
/** Whether obj is an object of the registry that the filter dropped (one lookup). */
bool droppedObject(const CObjectRegistry& r, int32_t obj)
{
	const auto it = r.objects().find(obj);
	return it != r.objects().end() && it->second.dropped;
}

/** The fast check of CClassifyingRouter::validate: IDs -1 or in [0, kFirstResolvedId), those >= 0
 * distinct (sorted copy, no allocation per reading). */
bool valid(const std::vector<TReading>& readings)
{
	std::vector<int32_t> ids;
	ids.reserve(readings.size());
	for (const TReading& r : readings)
	{
		if (r.id < -1 || r.id >= kFirstResolvedId) return false;
		if (r.id >= 0) ids.push_back(r.id);
	}
	std::sort(ids.begin(), ids.end());
	return std::adjacent_find(ids.begin(), ids.end()) == ids.end();
}
}  // namespace

void CClassifyingRouter::validate(const std::vector<TReading>& readings,
                                  const std::string& who) const
{
	if (valid(readings)) return;  // the loop below names the first bad reading
	std::set<int32_t> seen;
	for (size_t i = 0; i < readings.size(); ++i)
	{
		const int32_t id = readings[i].id;
		// Built only for an error message (not per reading: it was 3 % of a classify run).
		const auto where = [&]
		{ return "measurement " + std::to_string(i) + " (track ID " + std::to_string(id) + ")"; };
		if (id < -1)
			throw std::runtime_error(who + ": " + where() +
			                         ": feature_labels = classify takes track IDs >= 0 or -1 "
			                         "(association unknown)");
		if (id >= 0 && !seen.insert(id).second)
			throw std::runtime_error(who + ": duplicate " + where());
		if (id >= kFirstResolvedId)
			throw std::runtime_error(who + ": " + where() +
			                         ": IDs >= 1000000000 are reserved for the tracks of ID -1 "
			                         "readings (feature_labels = classify)");
	}
}

bool CClassifyingRouter::isMember(int32_t id, int32_t obj) const
{
	const auto it = m_tracks.find(id);
	return it != m_tracks.end() && it->second.cls == TrackClass::Moving && it->second.object == obj;
}

bool CClassifyingRouter::inconsistentWithObject(int32_t id, const TPoint2& z,
                                                const std::map<int32_t, TPoint2>& now) const
{
	const TTrack& t = m_tracks.at(id);
	const auto members = m_objectTracks.find(t.object);
	if (members == m_objectTracks.end()) return false;
	const double gate = chiSquareQuantile(m_p.reclassify_gate, 1);
	int compared = 0;
	int32_t other = -1;
	for (const int32_t o : members->second)
	{
		const auto zo = now.find(o);
		if (o == id || zo == now.end() || !isMember(o, t.object)) continue;
		const TRigidNow r = rigidNowTest(t.history, z, m_tracks.at(o).history, zo->second);
		if (r.past < 2) continue;
		if (r.z2 <= gate) return false;  // consistent with one of them: stays
		++compared;
		other = o;
	}
	// Against a single other feature both look inconsistent: the younger track leaves.
	return compared >= 2 || (compared == 1 && id > other);
}

int32_t CClassifyingRouter::restartTrack(int32_t id, int32_t externalId)
{
	const int32_t nid = m_unknown.newId();
	if (externalId >= 0) m_alias[externalId] = nid;
	TTrack& t = m_tracks.at(id);
	if (t.cls == TrackClass::Moving)
	{
		// A moving track leaves its object (its f_0 stays, unseen); a static one stays a
		// landmark of the map (the point it saw is still there).
		auto& members = m_objectTracks[t.object];
		members.erase(std::remove(members.begin(), members.end(), id), members.end());
		if (members.empty() && droppedObject(m_registry, t.object))
			m_objectTracks.erase(t.object);  // a dropped object's last track: nothing to keep
		m_tracks.erase(id);
		m_unknown.forget(id);
	}
	return nid;
}

void CClassifyingRouter::checkAssignments(int step, std::vector<TReading>& rd,
                                          const std::vector<TPoint2>& pts,
                                          const std::vector<int32_t>& external, TRoutedStep& out,
                                          std::set<int32_t>& held)
{
	std::map<int32_t, TPoint2> now;
	for (size_t i = 0; i < rd.size(); ++i)
		if (rd[i].id >= 0) now[rd[i].id] = pts[i];
	const double staticGate = chiSquareQuantile(m_p.reclassify_gate, 2);
	for (size_t i = 0; i < rd.size(); ++i)
	{
		const auto it = rd[i].id >= 0 ? m_tracks.find(rd[i].id) : m_tracks.end();
		if (it == m_tracks.end()) continue;
		TTrack& t = it->second;
		const bool gap = m_p.reuse_gap > 0 && step - t.last_seen >= m_p.reuse_gap;
		bool restart = false, split = false;
		if (t.cls == TrackClass::Moving && droppedObject(m_registry, t.object))
			restart = true;  // its object left the state (drop_object_after_unseen_steps)
		else if (t.cls == TrackClass::Static && gap && t.q_valid)
		{
			const Eigen::Vector2d nu = pts[i].p - t.q.p;
			restart = nu.dot((t.q.C + pts[i].C).inverse() * nu) > staticGate;
		}
		else if (t.cls == TrackClass::Moving && (gap || m_p.split_count > 0))
		{
			if (!inconsistentWithObject(rd[i].id, pts[i], now))
				t.split_streak = 0;
			else if (gap)
				restart = true;
			else if (++t.split_streak < m_p.split_count)
				held.insert(rd[i].id);
			else
				restart = split = true;
		}
		if (!restart) continue;
		++(split ? out.split : out.restarted);
		now.erase(rd[i].id);
		rd[i].id = restartTrack(rd[i].id, external[i]);
	}
}

bool CClassifyingRouter::rigidWithObject(const TTrack& t, int32_t obj) const
{
	const auto members = m_objectTracks.find(obj);
	if (members == m_objectTracks.end()) return false;
	int tested = 0;
	for (const int32_t o : members->second)
	{
		if (!isMember(o, obj)) continue;
		const TRigidTest r = rigidDistanceTest(t.history, m_tracks.at(o).history);
		if (r.common < 2) continue;
		if (r.mean_dist > m_p.group_max_dist ||
		    r.chi2 > chiSquareQuantile(m_p.group_prob, r.common - 1))
			return false;
		++tested;
	}
	return tested > 0;
}

int32_t CClassifyingRouter::joinableObject(const TTrack& t,
                                           const std::vector<int32_t>& exclude) const
{
	if (!m_p.join) return -1;
	// With hints: the objects of the track's own hint first; never one of another hint.
	for (const bool ownHintPass : {true, false})
	{
		if (ownHintPass && (!m_p.use_hints || t.hint < 0)) continue;
		for (const auto& [obj, members] : m_objectTracks)
		{
			if (members.empty() || !m_registry.has(obj) ||
			    std::find(exclude.begin(), exclude.end(), obj) != exclude.end() ||
			    hintsDiffer(t, obj) || (ownHintPass && objectHint(obj) != t.hint))
				continue;
			if (rigidWithObject(t, obj)) return obj;
		}
	}
	return -1;
}
}  // namespace dynslam::estimator
