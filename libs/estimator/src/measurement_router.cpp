#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/classifying_router.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/estimator/unknown_id_association.h>

#include <algorithm>
#include <stdexcept>

namespace dynslam::estimator
{
const char* toString(Route r)
{
	switch (r)
	{
		case Route::StaticKnown:
			return "static_known";
		case Route::StaticNew:
			return "static_new";
		case Route::ObjectFirstSighting:
			return "object_first_sighting";
		case Route::ObjectTimeT:
			return "object_time_t";
		case Route::Skip:
			return "skip";
	}
	return "?";
}

std::vector<TRoutedReading> TRoutedStep::with(Route r) const
{
	std::vector<TRoutedReading> out;
	for (const auto& m : readings)
		if (m.route == r) out.push_back(m);
	return out;
}

std::vector<TRoutedReading> TRoutedStep::statics() const
{
	std::vector<TRoutedReading> out;
	for (const auto& m : readings)
		if (m.route == Route::StaticKnown || m.route == Route::StaticNew) out.push_back(m);
	return out;
}

std::vector<TRoutedReading> TRoutedStep::objects() const
{
	std::vector<TRoutedReading> out;
	for (const auto& m : readings)
		if (m.route == Route::ObjectFirstSighting || m.route == Route::ObjectTimeT)
			out.push_back(m);
	return out;
}

void routeObjectReading(CObjectRegistry& registry, int step, TRoutedReading& m, TRoutedStep& out)
{
	switch (registry.registerReading(m.object, m.reading.id, m.feature, step))
	{
		case FeatureRole::FirstSighting:
			m.route = Route::ObjectFirstSighting;
			break;
		case FeatureRole::TimeT:
			m.route = Route::ObjectTimeT;
			break;
		case FeatureRole::Unknown:
			m.route = Route::Skip;
			++out.skipped_unknown_object_feature;
			break;
		case FeatureRole::Dropped:
			m.route = Route::Skip;
			++out.skipped_dropped_object;
			break;
	}
}

std::vector<TReading> readingsOf(const std::vector<TRoutedReading>& r)
{
	std::vector<TReading> out;
	out.reserve(r.size());
	for (const auto& m : r) out.push_back(m.reading);
	return out;
}

void CIdRangeRouter::validate(const std::vector<TReading>& readings, const std::string& who) const
{
	// The IDs seen so far, sorted (a step has tens of readings: cheaper than a std::set); the
	// messages are only built for an error.
	std::vector<int32_t> seen;
	seen.reserve(readings.size());
	const auto where = [&](size_t i)
	{
		return "measurement " + std::to_string(i) + " (landmark ID " +
		       std::to_string(readings[i].id) + ")";
	};
	for (size_t i = 0; i < readings.size(); ++i)
	{
		const int32_t id = readings[i].id;
		if (id == -1) continue;  // MRPT's unknown landmark: associated in route()
		if (ids::classify(id) == ids::IdKind::Invalid || id >= kFirstResolvedId)
			throw std::runtime_error(
			    who + ": " + where(i) +
			    " is in no known ID range (static landmarks 0..99999, features of moving objects "
			    "100000..999999999 as 100000 + 1000 x object + feature, -1 unknown; "
			    "dynslam/core/landmark_ids.h)");
		const auto it = std::lower_bound(seen.begin(), seen.end(), id);
		if (it != seen.end() && *it == id)
			throw std::runtime_error(who + ": duplicate " + where(i));
		seen.insert(it, id);
	}
}

void CIdRangeRouter::reset()
{
	m_registry.clear();
	m_statics.clear();
	m_next = kFirstResolvedId;
}

void CIdRangeRouter::addStatic(int32_t id)
{
	const auto it = std::lower_bound(m_statics.begin(), m_statics.end(), id);
	if (it == m_statics.end() || *it != id) m_statics.insert(it, id);
}

void CIdRangeRouter::resolveUnknown(TRoutedStep& out,
                                    const std::function<bool(int32_t)>& isKnownStatic)
{
	std::vector<size_t> unknown;
	std::vector<int32_t> readNow;  // landmarks read with their own ID in this step
	for (size_t i = 0; i < out.readings.size(); ++i)
		(out.readings[i].reading.id == -1 ? (void)unknown.push_back(i)
		                                  : (void)readNow.push_back(out.readings[i].reading.id));
	if (unknown.empty()) return;
	if (!m_assoc || !m_hasCtx || !m_ctx.static_innovation)
	{
		out.skipped_unknown_id += unknown.size();  // route stays Skip
		return;
	}
	// The predictions h (measurement space) with S = H P H^T + R of the static landmarks in the
	// state, as CRangeBearingKFSLAM2D gives them to data_association_full_covariance.
	std::sort(readNow.begin(), readNow.end());
	std::vector<TAssocTarget> pred;
	std::vector<Eigen::Vector2d> obs;
	for (size_t i : unknown) obs.push_back(out.readings[i].reading.z);
	const Eigen::Vector2d& z0 = obs.front();
	for (int32_t id : m_statics)
	{
		TStaticInnovation inn;
		if (std::binary_search(readNow.begin(), readNow.end(), id) || !isKnownStatic(id) ||
		    !m_ctx.static_innovation(id, z0, inn))
			continue;
		TAssocTarget t;
		t.id = id;
		t.pred.p = z0 - inn.nu;
		if (m_ctx.model == models::MeasurementModel::RangeBearing)
			t.pred.p[1] = models::wrapToPi(t.pred.p[1]);
		t.pred.C = inn.S;
		pred.push_back(t);
	}
	const std::vector<int> a = pred.empty() ? std::vector<int>(obs.size(), -1) : m_assoc(obs, pred);
	if (a.size() != obs.size())
		throw std::logic_error("CIdRangeRouter: the static association returned a wrong size");
	std::vector<int32_t> taken;
	for (size_t k = 0; k < unknown.size(); ++k)
	{
		TRoutedReading& m = out.readings[unknown[k]];
		const int j = a[k];
		const bool ok = j >= 0 && size_t(j) < pred.size() &&
		                std::find(taken.begin(), taken.end(), pred[size_t(j)].id) == taken.end();
		if (ok)
		{
			m.reading.id = pred[size_t(j)].id;
			m.route = Route::StaticKnown;
			taken.push_back(m.reading.id);
			++out.unknown_id_static;
		}
		else
		{
			m.reading.id = m_next++;
			m.route = Route::StaticNew;
			addStatic(m.reading.id);
			++out.unknown_id_new;
		}
	}
}

TRoutedStep CIdRangeRouter::route(int step, const std::vector<TReading>& readings,
                                  const std::function<bool(int32_t)>& isKnownStatic)
{
	TRoutedStep out;
	out.readings.reserve(readings.size());
	for (const auto& r : readings)
	{
		TRoutedReading m;
		m.reading = r;
		if (r.id == -1)
			m.route = Route::Skip;  // resolveUnknown below
		else if (ids::isStatic(r.id))
		{
			m.route = isKnownStatic(r.id) ? Route::StaticKnown : Route::StaticNew;
			if (m.route == Route::StaticNew) addStatic(r.id);
		}
		else
		{
			m.object = ids::objectOf(r.id);
			m.feature = ids::featureOf(r.id);
			routeObjectReading(m_registry, step, m, out);
		}
		out.readings.push_back(m);
	}
	resolveUnknown(out, isKnownStatic);
	return out;
}

int32_t CIdRangeRouter::featureId(int32_t object, int32_t feature) const
{
	return ids::objectFeatureId(object, feature);
}

std::unique_ptr<IMeasurementRouter> makeRouter(const std::string& feature_labels,
                                               const TClassifyParams* classify)
{
	return routers().make(feature_labels, {classify});
}
void IMeasurementRouter::mergeObjects(int32_t from, int32_t into)
{
	throw std::logic_error("router " + name() + " cannot merge object " + std::to_string(from) +
	                       " into " + std::to_string(into));
}
}  // namespace dynslam::estimator
