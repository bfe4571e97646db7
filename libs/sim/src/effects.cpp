/** @file effects.cpp
 * Missed detections, track breaks, anonymous IDs and clutter (issue 12; doc/simulator.md). */
#include "effects.h"

#include <dynslam/core/landmark_ids.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace dynslam::sim::detail
{
CReadingEffects::CReadingEffects(const io::TGroundTruth& gt, const TScenarioOptions& o,
                                 uint32_t seed)
    : m_o(o), m_e(o.effects), m_rng(uint32_t(uint64_t(seed) + 0x9E3779B9u))
{
	int32_t maxStatic = -1;
	std::vector<int32_t> ids;
	for (const auto& [id, p] : gt.landmarks)
	{
		ids.push_back(id);
		maxStatic = std::max(maxStatic, id);
	}
	m_nextStatic = maxStatic + 1;
	for (const io::TObjectGroundTruth& og : gt.objects)
	{
		for (int j = 0; j < og.num_features; ++j) ids.push_back(ids::objectFeatureId(og.object, j));
		m_nextFeature.push_back(og.num_features);
	}
	if (!m_e.anonymous_ids) return;
	// A uniform random permutation of 0..N-1 (Fisher-Yates; index from a 32-bit draw scaled
	// to [0, i], Lemire's multiply-shift).
	std::vector<int32_t> perm(ids.size());
	std::iota(perm.begin(), perm.end(), 0);
	for (size_t i = perm.size(); i > 1; --i)
	{
		const size_t j = size_t((uint64_t(m_rng.drawUniform32bit()) * uint64_t(i)) >> 32);
		std::swap(perm[i - 1], perm[j]);
	}
	for (size_t i = 0; i < ids.size(); ++i) m_anon[ids[i]] = perm[i];
	m_nextAnon = int32_t(ids.size());
}

int32_t CReadingEffects::initialId(int32_t true_id) const
{
	if (!m_e.anonymous_ids) return true_id;
	const auto it = m_anon.find(true_id);
	if (it == m_anon.end())
		throw std::logic_error("CReadingEffects: no anonymous ID for " + ids::describe(true_id));
	return it->second;
}

int32_t CReadingEffects::newTrackId(int32_t true_id)
{
	if (m_e.anonymous_ids) return m_nextAnon++;
	if (ids::isStatic(true_id))
	{
		if (m_nextStatic > ids::kStaticMax)
			throw std::runtime_error(
			    "[Effects] track breaks and clutter exhausted the static ID range 0..99999");
		return m_nextStatic++;
	}
	const int32_t obj = ids::objectOf(true_id);
	int32_t& j = m_nextFeature.at(size_t(obj));
	if (j >= ids::kFeaturesPerObject)
		throw std::runtime_error(
		    "[Effects] track breaks exhausted the 1000 feature IDs of object " +
		    std::to_string(obj));
	return ids::objectFeatureId(obj, j++);
}

int32_t CReadingEffects::clutterId()
{
	if (m_e.clutter_unknown_ids) return -1;
	if (m_e.anonymous_ids) return m_nextAnon++;
	if (m_nextStatic > ids::kStaticMax)
		throw std::runtime_error(
		    "[Effects] track breaks and clutter exhausted the static ID range 0..99999");
	return m_nextStatic++;
}

int32_t CReadingEffects::trackId(int32_t true_id, size_t k)
{
	TTrack& tr = m_tracks[true_id];
	if (tr.last_seen < 0)
		tr.id = initialId(true_id);
	else
	{
		// One draw per reading of an already seen track (when the probability is set), so the
		// draw sequence does not depend on the gap rule.
		bool brk = m_e.track_break_probability > 0 &&
		           m_rng.drawUniform(0.0, 1.0) < m_e.track_break_probability;
		if (m_e.track_break_gap > 0 && long(k) - tr.last_seen - 1 >= m_e.track_break_gap)
			brk = true;
		if (brk) tr.id = newTrackId(true_id);
	}
	tr.last_seen = long(k);
	return tr.id;
}

void CReadingEffects::apply(size_t k, mrpt::obs::CObservationBearingRange& obs,
                            std::vector<io::TReadingClass>& truth)
{
	using TMeas = mrpt::obs::CObservationBearingRange::TMeasurement;
	if (obs.sensedData.size() != truth.size())
		throw std::logic_error("CReadingEffects::apply: readings and truth rows differ");
	std::vector<TMeas> meas;
	std::vector<io::TReadingClass> rows;
	// 1) missed detections, one draw per true reading, 2) track IDs of the kept ones.
	std::vector<uint8_t> keep(truth.size(), 1);
	if (m_e.missed_detection_probability > 0)
		for (auto& kp : keep) kp = m_rng.drawUniform(0.0, 1.0) >= m_e.missed_detection_probability;
	for (size_t i = 0; i < truth.size(); ++i)
	{
		if (!keep[i]) continue;
		TMeas m = obs.sensedData[i];
		io::TReadingClass r = truth[i];
		r.id = m.landmarkID = trackId(r.true_id, k);
		// ID unknown in this reading (one draw per kept reading, only when the option is on).
		if (m_e.unknown_id_probability > 0 &&
		    m_rng.drawUniform(0.0, 1.0) < m_e.unknown_id_probability)
			r.id = m.landmarkID = -1;
		meas.push_back(m);
		rows.push_back(r);
	}
	// 3) clutter: uniform in the sensor's disc (r = R sqrt(1 - u), yaw uniform), noise-free.
	for (int c = 0; c < m_e.clutter_per_step; ++c)
	{
		const double u = m_rng.drawUniform(0.0, 1.0), a = m_rng.drawUniform(-M_PI, M_PI);
		TMeas m;
		m.range = float(std::max(m_o.sensor_range * std::sqrt(1.0 - u), 1e-6 * m_o.sensor_range));
		m.yaw = float(a);
		m.pitch = 0;
		m.covariance.setZero();
		m.landmarkID = clutterId();
		io::TReadingClass r;
		r.step = int(k);
		r.t = truth.empty() ? m_o.start_time + m_o.stepTime(k) : truth.front().t;
		r.id = m.landmarkID;
		r.cls = io::TrueClass::Clutter;
		meas.push_back(m);
		rows.push_back(r);
	}
	// 4) anonymous: the order of the observation must not tell static from moving either.
	if (m_e.anonymous_ids)
	{
		std::vector<size_t> order(meas.size());
		std::iota(order.begin(), order.end(), 0);
		std::stable_sort(order.begin(), order.end(),
		                 [&](size_t a, size_t b) { return rows[a].id < rows[b].id; });
		std::vector<TMeas> m2;
		std::vector<io::TReadingClass> r2;
		for (size_t i : order) m2.push_back(meas[i]), r2.push_back(rows[i]);
		meas.swap(m2);
		rows.swap(r2);
	}
	for (size_t i = 0; i < rows.size(); ++i) rows[i].index = int(i);
	obs.sensedData = std::move(meas);
	truth = std::move(rows);
}
}  // namespace dynslam::sim::detail
