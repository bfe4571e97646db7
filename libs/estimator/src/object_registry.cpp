#include <dynslam/estimator/object_registry.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
int TObjectEntry::indexOf(int32_t id) const
{
	const auto it = std::find(feature_ids.begin(), feature_ids.end(), id);
	return it == feature_ids.end() ? -1 : int(it - feature_ids.begin());
}

FeatureRole CObjectRegistry::registerReading(int32_t obj, int32_t id, int32_t feature, int step)
{
	auto it = m_objects.find(obj);
	if (it != m_objects.end() && it->second.dropped) return FeatureRole::Dropped;
	if (it == m_objects.end() || it->second.first_step == step)
	{
		TObjectEntry& o = m_objects[obj];
		o.first_step = step;
		o.feature_ids.push_back(id);
		o.feature_index.push_back(feature);
		o.founders = int(o.feature_ids.size());
		return FeatureRole::FirstSighting;
	}
	TObjectEntry& o = it->second;
	if (o.indexOf(id) >= 0) return FeatureRole::TimeT;
	++o.skipped_late_readings;
	const auto at = std::lower_bound(o.skipped_late_ids.begin(), o.skipped_late_ids.end(), id);
	if (at == o.skipped_late_ids.end() || *at != id) o.skipped_late_ids.insert(at, id);
	return FeatureRole::Unknown;
}

void CObjectRegistry::registerObject(int32_t obj, int first_step, const std::vector<int32_t>& ids,
                                     const std::vector<int32_t>& index)
{
	if (m_objects.count(obj))
		throw std::logic_error("CObjectRegistry::registerObject: object " + std::to_string(obj) +
		                       " exists");
	if (ids.empty() || ids.size() != index.size())
		throw std::logic_error("CObjectRegistry::registerObject: object " + std::to_string(obj) +
		                       ": empty or inconsistent feature set");
	TObjectEntry& o = m_objects[obj];
	o.first_step = first_step;
	o.feature_ids = ids;
	o.feature_index = index;
	o.founders = int(ids.size());
}

void CObjectRegistry::addFeature(int32_t obj, int32_t id, int32_t feature)
{
	const auto it = m_objects.find(obj);
	if (it == m_objects.end() || it->second.indexOf(id) >= 0)
		throw std::logic_error("CObjectRegistry::addFeature: object " + std::to_string(obj) +
		                       (it == m_objects.end() ? " does not exist" : " has feature ") +
		                       (it == m_objects.end() ? "" : std::to_string(id)));
	it->second.feature_ids.push_back(id);
	it->second.feature_index.push_back(feature);
}

void CObjectRegistry::recordDroppedPose(int32_t obj, const TPoseRecord& r, bool record)
{
	if (record) m_objects.at(obj).dropped_poses.push_back(r);
}

void CObjectRegistry::recordDroppedVelocity(int32_t obj, const TVelocityRecord& r, bool record)
{
	if (record) m_objects.at(obj).dropped_velocities.push_back(r);
}

bool CObjectRegistry::isTimeT(int32_t obj, int step) const
{
	const auto it = m_objects.find(obj);
	return it != m_objects.end() && it->second.first_step != step;
}
void CObjectRegistry::markDropped(int32_t obj)
{
	const auto it = m_objects.find(obj);
	if (it == m_objects.end())
		throw std::logic_error("CObjectRegistry::markDropped: unknown object " +
		                       std::to_string(obj));
	it->second.dropped = true;
}
}  // namespace dynslam::estimator
