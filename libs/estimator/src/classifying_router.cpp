/** CClassifyingRouter (classifying_router.h, doc/results/classification.md). */
#include <dynslam/core/models/measurement.h>
#include <dynslam/estimator/classifying_router.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace dynslam::estimator
{
namespace
{
/** A step's output with room for all its readings. */
TRoutedStep emptyStep(size_t readings)
{
	TRoutedStep s;
	s.readings.reserve(readings);
	return s;
}

}  // namespace

void TClassifyParams::validate() const
{
	const auto prob = [](double p, const char* key)
	{
		if (!(p > 0 && p < 1))
			throw std::invalid_argument(std::string(key) + " = " + std::to_string(p) +
			                            ": must be a probability in (0, 1)");
	};
	prob(alpha, "classify_alpha");
	prob(beta, "classify_beta");
	prob(group_prob, "classify_group_prob");
	prob(reclassify_gate, "classify_reclassify_gate");
	if (alpha + beta >= 1)
		throw std::invalid_argument("classify_alpha + classify_beta must be < 1");
	if (!(motion_std > 0) || !std::isfinite(motion_std))
		throw std::invalid_argument("classify_motion_std must be > 0");
	if (max_window < 2) throw std::invalid_argument("classify_max_window must be >= 2");
	if (forget_steps < 1) throw std::invalid_argument("classify_forget_steps must be >= 1");
	if (!(group_max_dist > 0)) throw std::invalid_argument("classify_group_max_dist must be > 0");
	if (reclassify_count < 0)
		throw std::invalid_argument("classify_reclassify_count must be >= 0 (0: off)");
	if (stop_count < 0) throw std::invalid_argument("classify_stop_count must be >= 0 (0: off)");
	if (reuse_gap < 0) throw std::invalid_argument("classify_reuse_gap must be >= 0 (0: off)");
	if (split_count < 0) throw std::invalid_argument("classify_split_count must be >= 0 (0: off)");
	if (link_gap < 1) throw std::invalid_argument("classify_link_gap must be >= 1");
	if (merge_live_window < 0)
		throw std::invalid_argument("classify_merge_live_window must be >= 0 (0: automatic)");
	assoc.validate();
}

CClassifyingRouter::CClassifyingRouter(const TClassifyParams& p) : m_p(p), m_unknown(p.assoc)
{
	m_p.validate();
}

double CClassifyingRouter::upperThreshold() const { return std::log((1 - m_p.beta) / m_p.alpha); }
double CClassifyingRouter::lowerThreshold() const { return std::log(m_p.beta / (1 - m_p.alpha)); }

void CClassifyingRouter::reset()
{
	m_tracks.clear();
	m_live.clear();
	m_registry.clear();
	m_objectTracks.clear();
	m_alias.clear();
	m_identity.clear();
	m_continued.clear();
	m_nextObject = 0;
	m_lastStep = -1;
	m_ctx.reset();
	m_unknown.reset();
	m_rawNow.clear();
}

int32_t CClassifyingRouter::featureId(int32_t object, int32_t feature) const
{
	const TObjectEntry& e = m_registry.at(object);
	for (size_t i = 0; i < e.feature_index.size(); ++i)
		if (e.feature_index[i] == feature) return e.feature_ids[i];
	throw std::out_of_range("CClassifyingRouter::featureId: object " + std::to_string(object) +
	                        " has no feature " + std::to_string(feature));
}

void CClassifyingRouter::remember(TTrack& t, const TPoint2& z, int step, int keep)
{
	// A full history reuses its oldest node for the new step (no allocation per reading); the
	// kept entries are the same as by insert-then-erase.
	if (int(t.history.size()) >= keep && !t.history.empty() && t.history.begin()->first < step &&
	    !t.history.count(step))
	{
		auto node = t.history.extract(t.history.begin());
		node.key() = step;
		node.mapped() = z;
		t.history.insert(std::move(node));
	}
	else
		t.history[step] = z;
	while (int(t.history.size()) > keep) t.history.erase(t.history.begin());
}

void CClassifyingRouter::predictTracks(int step, TRoutedStep& out,
                                       const std::function<bool(int32_t)>& isKnownStatic)
{
	const int steps = m_lastStep < 0 ? 0 : step - m_lastStep;
	m_lastStep = step;
	const TStaticMotion motion(m_ctx->u, m_ctx->U);  // rotations once per step, not per track
	// Only the live tracks (m_live, in ID order as m_tracks): a track without a valid filter,
	// or moving without stop_count, has nothing to do here until it is read again.
	for (auto live = m_live.begin(); live != m_live.end();)
	{
		const auto it = m_tracks.find(*live);
		if (it == m_tracks.end() || !needsPrediction(it->second))
		{
			live = m_live.erase(live);
			continue;
		}
		TTrack& t = it->second;
		if (t.cls != TrackClass::Moving && step - t.last_seen > m_p.forget_steps)
		{
			if (t.cls == TrackClass::Candidate)
			{
				if (m_p.candidate_landmarks && isKnownStatic(it->first))
					out.dropped_candidates.push_back(it->first);
				m_unknown.forget(it->first);  // its motion goes with it (as restartTrack's)
				m_tracks.erase(it);
				live = m_live.erase(live);
				continue;
			}
			t.q_valid = false;  // a static track seen again restarts its filter
			live = m_live.erase(live);
			continue;
		}
		if (steps > 0) t.q = predictStatic(t.q, motion);
		++live;
	}
}

bool CClassifyingRouter::needsPrediction(const TTrack& t) const
{
	return t.q_valid && (t.cls != TrackClass::Moving || m_p.stop_count > 0);
}

std::optional<TrackClass> CClassifyingRouter::addEvidence(TTrack& t, const TPoint2& z, int step)
{
	if (!t.q_valid)
	{
		t.q = z;
		t.q_valid = true;
		return std::nullopt;
	}
	const Eigen::Vector2d nu = z.p - t.q.p;
	const Eigen::Matrix2d S = t.q.C + z.C;
	const double gap = std::max(1, step - t.last_seen);
	const Eigen::Matrix2d Q = Eigen::Matrix2d::Identity() * (m_p.motion_std * m_p.motion_std * gap);
	t.llr += movingLogLikelihoodRatio(nu, S, Q);
	const Eigen::Matrix2d K = t.q.C * S.inverse();
	t.q.p += K * nu;
	t.q.C = (Eigen::Matrix2d::Identity() - K) * t.q.C;
	t.q.C = 0.5 * (t.q.C + t.q.C.transpose());
	if (t.llr >= upperThreshold()) return TrackClass::Moving;
	if (t.llr <= lowerThreshold()) return TrackClass::Static;
	if (t.sightings + 1 >= m_p.max_window)
		return t.llr > 0 ? TrackClass::Moving : TrackClass::Static;
	return std::nullopt;
}

void CClassifyingRouter::makeMoving(int32_t id, TTrack& t, int step,
                                    std::vector<int32_t>& newObjects, TRoutedStep& out,
                                    const std::vector<int32_t>& exclude)
{
	t.cls = TrackClass::Moving;
	t.q_valid = false;
	t.decided_step = step;
	for (const int32_t obj : newObjects)
	{
		std::vector<int32_t>& members = m_objectTracks[obj];
		bool rigid = !hintsDiffer(t, obj);  // another box: never one object
		for (const int32_t other : members)
		{
			const TRigidTest r = rigidDistanceTest(t.history, m_tracks.at(other).history);
			rigid = rigid && r.common >= 2 && r.mean_dist <= m_p.group_max_dist &&
			        r.chi2 <= chiSquareQuantile(m_p.group_prob, r.common - 1);
		}
		if (!rigid) continue;
		t.object = obj;
		t.feature = int32_t(members.size());
		members.push_back(id);
		return;
	}
	// Late joining: an object of an earlier step (not for converted landmarks, whose object
	// starts before this step with its f_0 from the landmarks).
	if (!t.converting)
		if (const int32_t obj = joinableObject(t, exclude); obj >= 0)
		{
			t.object = obj;
			t.feature = int32_t(m_registry.at(obj).feature_ids.size());
			m_registry.addFeature(obj, id, t.feature);
			m_objectTracks[obj].push_back(id);
			++out.joined;
			return;
		}
	t.object = m_nextObject++;
	t.feature = 0;
	m_objectTracks[t.object] = {id};
	newObjects.push_back(t.object);
}

CClassifyingRouter::Act CClassifyingRouter::classifyOne(
    int32_t id, const TPoint2& z, int step, TRoutedStep& out, bool& candidate,
    std::vector<int32_t>& turnedMoving, const std::function<bool(int32_t)>& isKnownStatic)
{
	TTrack& t = m_tracks[id];
	m_live.insert(id);  // read: predictTracks decides from the next step on
	if (t.first_seen < 0) t.first_seen = step;
	remember(t, z, step, m_p.max_window + 2);
	Act act = Act::Skip;
	if (t.cls == TrackClass::Candidate)
	{
		const std::optional<TrackClass> d = addEvidence(t, z, step);
		if (d == TrackClass::Static)
		{
			t.cls = TrackClass::Static;
			t.decided_step = step;
			t.last_good = step;
			act = Act::Static;
		}
		else if (d == TrackClass::Moving)
		{
			turnedMoving.push_back(id);
			if (m_p.candidate_landmarks && isKnownStatic(id)) out.dropped_candidates.push_back(id);
		}
		else
		{
			++out.candidates;
			candidate = true;
			// The first reading: a candidate landmark, not an update (see the header).
			if (m_p.candidate_landmarks && t.sightings == 0) act = Act::Static;
		}
	}
	else if (t.cls == TrackClass::Static)
	{
		if (checkStatic(id, t, z, step))
			act = Act::Static;
		else if (t.bad_streak >= m_p.reclassify_count)
			reclassifyStatic(id, t, out, turnedMoving, isKnownStatic);
		else
			++out.held;
	}
	else if (stoppedEvidence(t, z))
	{
		// Its object stopped: a static track again, its landmark starts with this reading.
		t.cls = TrackClass::Static;
		t.object = t.feature = -1;
		t.decided_step = t.last_good = step;
		t.bad_streak = t.still_streak = 0;
		++out.stopped;
		act = Act::Static;
	}
	else
		act = Act::Moving;
	++t.sightings;
	t.last_seen = step;
	return act;
}

void CClassifyingRouter::registerConverted(const std::vector<int32_t>& objects, int step,
                                           TRoutedStep& out)
{
	for (const int32_t obj : objects)
	{
		const std::vector<int32_t>& members = m_objectTracks.at(obj);
		// Time 0: the last step at which a member still read as static (the landmarks' estimate
		// is where the features were then); always before this step.
		int first = -1;
		std::vector<int32_t> index;
		for (const int32_t id : members)
		{
			TTrack& t = m_tracks.at(id);
			first = std::max(first, t.last_good);
			index.push_back(t.feature);
			out.converted.push_back({id, obj, t.feature});
			t.converting = false;
		}
		m_registry.registerObject(obj, std::min(first, step - 1), members, index);
	}
}

void CClassifyingRouter::routeMoving(TRoutedReading& m, const TTrack& t, int step, TRoutedStep& out)
{
	m.object = t.object;
	m.feature = t.feature;
	routeObjectReading(m_registry, step, m, out);
}

void CClassifyingRouter::resolveUnknownIds(int step, std::vector<TReading>& rd,
                                           const std::vector<TPoint2>& pts, TRoutedStep& out)
{
	// Without a -1 reading nothing below has an effect (resolve returns the IDs as they are).
	if (std::none_of(rd.begin(), rd.end(), [](const TReading& r) { return r.id == -1; })) return;
	std::vector<int32_t> ids;
	std::set<int32_t> explicitIds;
	for (const TReading& r : rd)
	{
		ids.push_back(r.id);
		if (r.id >= 0) explicitIds.insert(r.id);
	}
	if (explicitIds.size() == rd.size()) return;
	// The reading noise at a predicted point, added to the prediction's covariance.
	const auto withNoise = [&](TPoint2 q)
	{
		const Eigen::Vector2d z = models::observeFromSensor(m_ctx->model, Eigen::Vector3d::Zero(),
		                                                    m_ctx->sensor_pose, q.p);
		q.C += readingInRobotFrame(*m_ctx, z).C;
		return q;
	};
	std::vector<TAssocTarget> statics, moving;
	for (const auto& [id, t] : m_tracks)
		if (t.cls != TrackClass::Moving && t.q_valid && !explicitIds.count(id))
			statics.push_back({id, withNoise(t.q)});
	// Moving and candidate tracks seen twice: constant velocity; candidates seen once: the
	// second-sighting radius. Static tracks are the static association's.
	std::vector<TTrackPrediction> once;
	for (const TTrackPrediction& p : m_unknown.predictions(step, m_p.motion_std))
	{
		const auto it = m_tracks.find(p.target.id);
		if (it == m_tracks.end() || it->second.cls == TrackClass::Static ||
		    explicitIds.count(p.target.id))
			continue;
		if (p.has_vel)
			moving.push_back({p.target.id, withNoise(p.target.pred)});
		else if (it->second.cls == TrackClass::Candidate)
			once.push_back(p);
	}
	const TResolvedIds r = m_unknown.resolve(ids, pts, statics, moving, once);
	for (size_t i = 0; i < rd.size(); ++i) rd[i].id = r.ids[i];
	out.unknown_id_static += r.to_static;
	out.unknown_id_moving += r.to_moving + r.to_second;
	out.unknown_id_new += r.new_tracks;
}

TRoutedStep CClassifyingRouter::route(int step, const std::vector<TReading>& readings,
                                      const std::function<bool(int32_t)>& isKnownStatic)
{
	if (!m_ctx) throw std::logic_error("CClassifyingRouter::route: setContext() was not called");
	TRoutedStep out = emptyStep(readings.size());
	predictTracks(step, out, isKnownStatic);
	std::vector<TReading> rd = readings;  // -1 IDs resolved below (if active)
	std::vector<TPoint2> pts;
	std::vector<int32_t> external;  // the input IDs
	for (TReading& r : rd)
	{
		pts.push_back(readingInRobotFrame(*m_ctx, r.z));
		external.push_back(r.id);
		if (const auto a = m_alias.find(r.id); a != m_alias.end()) r.id = a->second;
	}
	if (predictsMotion()) m_unknown.predict(m_ctx->u, m_ctx->U);
	if (m_unknown.active()) resolveUnknownIds(step, rd, pts, out);
	std::set<int32_t> held;  // moving readings inconsistent with their object, held back
	checkAssignments(step, rd, pts, external, out, held);
	m_rawNow.clear();  // its only reader: mapInnovation (classify_static_test = map)
	for (const TReading& r : rd)
		if (m_p.static_test == TClassifyParams::StaticTest::Map && r.id >= 0) m_rawNow[r.id] = r.z;
	std::vector<Act> act(rd.size(), Act::Skip);
	std::vector<bool> candidate(rd.size(), false);
	std::vector<int32_t> turnedMoving;  // decided (or reclassified) moving now, in order
	for (size_t i = 0; i < rd.size(); ++i)
	{
		if (rd[i].id < 0)
		{
			++out.skipped_unknown_id;
			continue;
		}
		bool c = false;
		noteHint(m_tracks[rd[i].id], rd[i].hint, out);
		act[i] = classifyOne(rd[i].id, pts[i], step, out, c, turnedMoving, isKnownStatic);
		candidate[i] = c;
	}
	// Converted landmarks (surgery) group only with each other: their object's time 0 is
	// before this step, while a fresh object's is this step.
	std::vector<int32_t> newObjects, convertedObjects;
	for (const int32_t id : turnedMoving)
	{
		TTrack& t = m_tracks.at(id);
		std::vector<int32_t> exclude = newObjects;
		exclude.insert(exclude.end(), convertedObjects.begin(), convertedObjects.end());
		makeMoving(id, t, step, t.converting ? convertedObjects : newObjects, out, exclude);
	}
	registerConverted(convertedObjects, step, out);
	if (links())
	{
		std::map<int32_t, TPoint2> now;
		for (size_t i = 0; i < rd.size(); ++i)
			if (rd[i].id >= 0) now[rd[i].id] = pts[i];
		linkNewObjects(step, newObjects, now, out);
	}
	for (size_t i = 0; i < rd.size(); ++i)
	{
		TRoutedReading m;
		m.reading = rd[i];
		m.candidate = candidate[i];
		const int32_t id = rd[i].id;
		const auto it = id >= 0 ? m_tracks.find(id) : m_tracks.end();
		if (it != m_tracks.end() && it->second.cls == TrackClass::Moving)
			act[i] = held.count(id) ? Act::Skip : Act::Moving;
		if (held.count(id)) ++out.held;
		if (act[i] == Act::Static && m.candidate)
			m.route = isKnownStatic(id) ? Route::Skip : Route::StaticNew;
		else if (act[i] == Act::Static)
			m.route = isKnownStatic(id) ? Route::StaticKnown : Route::StaticNew;
		else if (act[i] == Act::Moving)
			routeMoving(m, it->second, step, out);
		if (m.object >= 0)
		{
			const auto root = m_identity.find(m.object);
			m.identity = root == m_identity.end() ? m.object : root->second;
		}
		if (predictsMotion() && id >= 0) m_unknown.observe(id, pts[i], step);
		out.readings.push_back(m);
	}
	countGroupHintConflicts(out);
	return out;
}
}  // namespace dynslam::estimator
