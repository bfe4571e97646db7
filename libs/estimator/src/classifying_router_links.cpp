/** CClassifyingRouter: detection-group hints and the links of new objects to lost ones after a
 * track break (doc/results/classification.md, "Hints and links after a track break"). */
#include <dynslam/estimator/classifying_router.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
void CClassifyingRouter::noteHint(TTrack& t, int32_t hint, TRoutedStep& out) const
{
	if (!m_p.use_hints || hint < 0) return;
	if (t.hint < 0)
		t.hint = hint;
	else if (t.hint != hint)
		++out.hint_track_conflicts;  // the track keeps its first hint
}

int32_t CClassifyingRouter::objectHint(int32_t obj) const
{
	const auto members = m_objectTracks.find(obj);
	if (members == m_objectTracks.end()) return -1;
	for (const int32_t id : members->second)
		if (const auto it = m_tracks.find(id); it != m_tracks.end() && it->second.hint >= 0)
			return it->second.hint;
	return -1;
}

bool CClassifyingRouter::hintsDiffer(const TTrack& t, int32_t obj) const
{
	if (!m_p.use_hints || t.hint < 0) return false;
	const int32_t h = objectHint(obj);
	return h >= 0 && h != t.hint;
}

namespace
{
/** A lost object or a new one: the centroid of its features (robot frame, this step; for a
 * lost one predicted with constant velocity) and its mean displacement per step. */
struct TObjMotion
{
	int32_t obj = -1;
	Eigen::Vector2d c = Eigen::Vector2d::Zero(), v = Eigen::Vector2d::Zero();
	int last = -1;  ///< lost: the last step any feature was seen; new: the first sighting
	int nv = 0;     ///< features with a velocity
};
}  // namespace

bool CClassifyingRouter::newObjectMotion(int32_t obj, int step,
                                         const std::map<int32_t, TPoint2>& now, Eigen::Vector2d& c,
                                         Eigen::Vector2d& v, int& first) const
{
	c = v = Eigen::Vector2d::Zero();
	first = step;
	int n = 0, nv = 0;
	for (const int32_t id : m_objectTracks.at(obj))
	{
		first = std::min(first, m_tracks.at(id).first_seen);
		const auto z = now.find(id);
		if (z == now.end()) continue;
		c += z->second.p, ++n;
		Eigen::Vector2d vi;
		if (m_unknown.velocityWith(id, z->second, step, vi)) v += vi, ++nv;
	}
	if (n == 0 || nv == 0) return false;
	c /= n;
	v /= nv;
	return true;
}

void CClassifyingRouter::linkNewObjects(int step, const std::vector<int32_t>& newObjects,
                                        const std::map<int32_t, TPoint2>& now, TRoutedStep& out)
{
	if (!links() || newObjects.empty()) return;
	const bool hintsOnly = m_p.link == TClassifyParams::Link::Hints;
	// Each object track's constant-velocity prediction (only those: the predictions of every
	// track ever read would cost the length of the run at every step with a new object).
	std::map<int32_t, TTrackPrediction> pred;
	for (const auto& [obj, members] : m_objectTracks)
		for (const int32_t id : members)
			if (const auto p = m_unknown.prediction(id, step, m_p.motion_std)) pred[id] = *p;
	std::vector<TObjMotion> lost;
	for (const auto& [obj, members] : m_objectTracks)
	{
		if (m_continued.count(obj) ||
		    std::find(newObjects.begin(), newObjects.end(), obj) != newObjects.end())
			continue;
		TObjMotion l;
		l.obj = obj;
		int n = 0;
		for (const int32_t id : members)
		{
			const auto p = pred.find(id);
			if (!isMember(id, obj) || p == pred.end()) continue;
			l.last = std::max(l.last, m_tracks.at(id).last_seen);
			l.c += p->second.target.pred.p;
			++n;
			if (p->second.has_vel) l.v += p->second.vel, ++l.nv;
		}
		if (n == 0 || l.nv == 0) continue;
		l.c /= n;
		l.v /= l.nv;
		lost.push_back(l);
	}
	const double gate = chiSquareQuantile(m_p.group_prob, 2);
	const double half = 0.5 * m_p.group_max_dist;  // two subsets of one object: centroids apart
	const double s2 = m_p.motion_std * m_p.motion_std;
	for (const int32_t obj : newObjects)
	{
		TObjMotion o;
		o.obj = obj;
		if (!newObjectMotion(obj, step, now, o.c, o.v, o.last)) continue;
		const int32_t hint = m_p.use_hints ? objectHint(obj) : -1;
		if (hintsOnly && hint < 0) continue;
		std::vector<size_t> passed, same;
		for (size_t i = 0; i < lost.size(); ++i)
		{
			const TObjMotion& l = lost[i];
			if (l.last >= o.last || o.last - l.last > m_p.link_gap) continue;
			const int32_t lh = m_p.use_hints ? objectHint(l.obj) : -1;
			if (hint >= 0 && lh >= 0 && lh != hint) continue;  // another box
			// Motion evidence: the velocity (displacement per step) changed by at most
			// motion_std per axis, the position within the prediction's gate, whose spread grows
			// as that velocity uncertainty times the gap.
			const double g = step - l.last;
			if ((o.v - l.v).squaredNorm() > gate * s2) continue;
			if ((o.c - l.c).squaredNorm() > gate * (s2 * g * g + half * half)) continue;
			passed.push_back(i);
			if (hint >= 0 && lh == hint) same.push_back(i);
		}
		// With its hint: the lost objects of that hint; without: all that passed. The nearest
		// (position distance normalised by the gate's spread) is linked.
		const std::vector<size_t>& cand = same.empty() && !hintsOnly ? passed : same;
		if (cand.empty()) continue;
		if (cand.size() > 1) ++out.link_ambiguous;
		const auto dist = [&](size_t i)
		{
			const double g = step - lost[i].last;
			return (o.c - lost[i].c).squaredNorm() / (s2 * g * g + half * half);
		};
		const size_t best = *std::min_element(
		    cand.begin(), cand.end(), [&](size_t a, size_t b) { return dist(a) < dist(b); });
		const int32_t from = lost[best].obj;
		const auto root = m_identity.find(from);
		m_identity[obj] = root == m_identity.end() ? from : root->second;
		m_continued.insert(from);
		lost.erase(lost.begin() + long(best));
		++out.linked;
		if (m_p.merge_linked) out.merges.push_back({obj, from});
	}
}

void CClassifyingRouter::countGroupHintConflicts(TRoutedStep& out) const
{
	if (!m_p.use_hints) return;
	std::map<int32_t, std::set<int32_t>> hints;  // object -> the hints of its readings now
	for (const TRoutedReading& m : out.readings)
		if ((m.route == Route::ObjectTimeT || m.route == Route::ObjectFirstSighting) &&
		    m.object >= 0 && m.reading.hint >= 0)
			hints[m.object].insert(m.reading.hint);
	for (const auto& [obj, h] : hints)
		if (h.size() > 1) ++out.hint_group_conflicts;
}
bool CClassifyingRouter::allowsMerge(int32_t a, int32_t b) const
{
	if (!m_p.use_hints) return true;
	const int32_t ha = objectHint(a), hb = objectHint(b);
	return ha < 0 || hb < 0 || ha == hb;
}

void CClassifyingRouter::mergeObjects(int32_t from, int32_t into)
{
	if (from == into || !m_objectTracks.count(from) || !m_objectTracks.count(into) ||
	    !m_registry.has(from) || !m_registry.has(into))
		throw std::logic_error("CClassifyingRouter::mergeObjects: cannot merge object " +
		                       std::to_string(from) + " into " + std::to_string(into));
	// from's features (its f_0 in the filter, now in into's frame) follow into's, in their order.
	const TObjectEntry e = m_registry.at(from);
	for (const int32_t id : m_objectTracks.at(from))
	{
		TTrack& t = m_tracks.at(id);
		if (!isMember(id, from)) continue;
		t.object = into;
		t.feature = -1;  // a member without an f_0 (never the case at a link): skipped, counted
		if (e.indexOf(id) >= 0)
		{
			t.feature = int32_t(m_registry.at(into).feature_ids.size());
			m_registry.addFeature(into, id, t.feature);
		}
		m_objectTracks[into].push_back(id);
	}
	m_objectTracks.erase(from);
	m_registry.erase(from);
	m_identity.erase(from);
	m_continued.erase(into);  // into lives on: it may be lost and continued again
}
}  // namespace dynslam::estimator
