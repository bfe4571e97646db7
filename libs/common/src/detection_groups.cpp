#include <dynslam/common/detection_groups.h>

#include <set>
#include <sstream>
#include <stdexcept>

namespace dynslam
{
mrpt::obs::CObservationComment::Ptr makeDetectionGroups(const std::vector<int32_t>& ids,
                                                        const std::vector<int32_t>& groups)
{
	if (ids.size() != groups.size())
		throw std::invalid_argument("makeDetectionGroups: " + std::to_string(ids.size()) +
		                            " IDs but " + std::to_string(groups.size()) + " groups");
	auto c = mrpt::obs::CObservationComment::Create();
	c->sensorLabel = kDetectionGroupsLabel;
	std::ostringstream t;
	t << kDetectionGroupsLabel << "\n# index landmarkID group\n";
	for (size_t i = 0; i < ids.size(); ++i)
	{
		if (groups[i] < -1)
			throw std::invalid_argument("makeDetectionGroups: group " + std::to_string(groups[i]) +
			                            " of reading " + std::to_string(i) + " (>= 0 or -1)");
		if (groups[i] >= 0) t << i << ' ' << ids[i] << ' ' << groups[i] << '\n';
	}
	c->text = t.str();
	return c;
}

void readDetectionGroups(const mrpt::obs::CSensoryFrame& SF,
                         std::vector<estimator::TReading>& readings, const std::string& who)
{
	for (const auto& o : SF)
	{
		const auto c = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(o);
		if (!c) continue;
		std::istringstream in(c->text);
		std::string line;
		if (!std::getline(in, line)) continue;
		while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
		if (line != kDetectionGroupsLabel) continue;  // another comment
		std::set<long> seen;
		for (int n = 2; std::getline(in, line); ++n)
		{
			const auto first = line.find_first_not_of(" \t\r");
			if (first == std::string::npos || line[first] == '#') continue;
			const std::string where = who + ": " + kDetectionGroupsLabel + " comment, line " +
			                          std::to_string(n) + " '" + line + "'";
			std::istringstream ls(line);
			long index = 0, id = 0, group = 0;
			std::string rest;
			if (!(ls >> index >> id >> group) || (ls >> rest))
				throw std::runtime_error(where + ": expected '<index> <landmarkID> <group>'");
			if (index < 0 || size_t(index) >= readings.size())
				throw std::runtime_error(where + ": index out of range (the step has " +
				                         std::to_string(readings.size()) + " readings)");
			if (readings[size_t(index)].id != id)
				throw std::runtime_error(where + ": reading " + std::to_string(index) + " has ID " +
				                         std::to_string(readings[size_t(index)].id));
			if (group < 0 || group > INT32_MAX)
				throw std::runtime_error(where + ": a group is an ID >= 0");
			if (!seen.insert(index).second)
				throw std::runtime_error(where + ": reading " + std::to_string(index) +
				                         " listed twice");
			readings[size_t(index)].hint = int32_t(group);
		}
	}
}
}  // namespace dynslam
