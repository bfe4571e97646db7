#include <dynslam/core/landmark_ids.h>

#include <stdexcept>

namespace dynslam::ids
{
int32_t objectFeatureId(int32_t obj, int32_t k)
{
	if (obj < 0 || obj > kMaxObject)
		throw std::out_of_range("objectFeatureId: object index " + std::to_string(obj) +
		                        " outside [0, " + std::to_string(kMaxObject) + "]");
	if (k < 0 || k >= kFeaturesPerObject)
		throw std::out_of_range("objectFeatureId: feature index " + std::to_string(k) +
		                        " outside [0, " + std::to_string(kFeaturesPerObject - 1) + "]");
	return kObjectBase + obj * kFeaturesPerObject + k;
}

std::string describe(int32_t id)
{
	switch (classify(id))
	{
		case IdKind::Static:
			return "static landmark " + std::to_string(id);
		case IdKind::ObjectFeature:
			return "object " + std::to_string(objectOf(id)) + " feature " +
			       std::to_string(featureOf(id));
		default:
			return "invalid landmark ID " + std::to_string(id);
	}
}
}  // namespace dynslam::ids
