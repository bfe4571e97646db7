#include <dynslam/eval/object_matching.h>

#include <stdexcept>
#include <string>

namespace dynslam::eval
{
std::map<int32_t, int32_t> matchObjectsByReadings(const std::vector<int32_t>& estObject,
                                                  const std::vector<TReadingClass>& truth)
{
	if (estObject.size() != truth.size())
		throw std::invalid_argument("matchObjectsByReadings: " + std::to_string(estObject.size()) +
		                            " estimated readings, " + std::to_string(truth.size()) +
		                            " in the class ground truth");
	std::map<int32_t, std::map<int32_t, size_t>> votes;  // estimated -> true -> readings
	for (size_t i = 0; i < estObject.size(); ++i)
		if (estObject[i] >= 0) ++votes[estObject[i]][truth[i].object < 0 ? -1 : truth[i].object];
	std::map<int32_t, int32_t> match;
	for (const auto& [est, counts] : votes)
	{
		int32_t best = -1;
		size_t bestN = 0;
		for (const auto& [obj, n] : counts)  // ascending: a tie keeps the smaller object >= 0
			if (obj >= 0 && n > bestN)
			{
				best = obj;
				bestN = n;
			}
		const auto none = counts.find(-1);
		if (none != counts.end() && none->second > bestN) best = -1;
		match[est] = best;
	}
	return match;
}

TRunEstimates withMatchedObjects(const TRunEstimates& est, const std::map<int32_t, int32_t>& match)
{
	auto to = [&](int32_t o)
	{
		const auto it = match.find(o);
		return it == match.end() ? int32_t(-1) : it->second;
	};
	TRunEstimates out = est;
	for (auto& p : out.object_poses) p.object = to(p.object);
	for (auto& f : out.object_features) f.object = to(f.object);
	return out;
}

std::optional<TVelocityErrors> classifyingVelocityErrors(const TGroundTruth& gt,
                                                         const TRunEstimates& est,
                                                         const std::vector<int32_t>& estObject,
                                                         const std::vector<TReadingClass>* truth)
{
	if (!truth) return std::nullopt;
	return objectVelocityErrors(gt,
	                            withMatchedObjects(est, matchObjectsByReadings(estObject, *truth)));
}

void blankObjectColumns(TRunMetrics& m)
{
	for (auto& o : m.objects)
	{
		const int32_t id = o.object;
		o = TObjectMetrics();
		o.object = id;
	}
}
}  // namespace dynslam::eval
