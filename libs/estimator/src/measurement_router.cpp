#include <dynslam/estimator/classifying_router.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/landmark_ids.h>

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
		if (ids::classify(id) == ids::IdKind::Invalid)
			throw std::runtime_error(
			    who + ": " + where(i) +
			    " is in no known ID range (static 0..99999, object features >= 100000; see "
			    "dynslam/landmark_ids.h)");
		const auto it = std::lower_bound(seen.begin(), seen.end(), id);
		if (it != seen.end() && *it == id)
			throw std::runtime_error(who + ": duplicate " + where(i));
		seen.insert(it, id);
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
		if (ids::isStatic(r.id))
			m.route = isKnownStatic(r.id) ? Route::StaticKnown : Route::StaticNew;
		else
		{
			m.object = ids::objectOf(r.id);
			m.feature = ids::featureOf(r.id);
			routeObjectReading(m_registry, step, m, out);
		}
		out.readings.push_back(m);
	}
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
