/** The layout as MRPT's 2-dof slots and the landmark ID -> block index (reader.h). */
#include <algorithm>

#include "reader.h"

namespace dynslam::ekf::results
{
using estimator::BlockKind;
using estimator::TBlock;

void assignInPlace(std::map<int32_t, size_t>& map, std::vector<std::pair<int32_t, size_t>>& pairs)
{
	std::stable_sort(pairs.begin(), pairs.end(),
	                 [](const auto& a, const auto& b) { return a.first < b.first; });
	auto it = map.begin();
	for (size_t i = 0; i < pairs.size(); ++i)
	{
		if (i + 1 < pairs.size() && pairs[i + 1].first == pairs[i].first) continue;
		const auto& [id, block] = pairs[i];
		while (it != map.end() && it->first < id) it = map.erase(it);
		if (it != map.end() && it->first == id)
			(it++)->second = block;
		else
			map.emplace_hint(it, id, block);
	}
	map.erase(it, map.end());
}

void slotsOf(const estimator::CPaddedLayout& layout, std::vector<TSlot>& slots,
             std::vector<std::pair<int32_t, size_t>>* statics)
{
	slots.clear();
	if (statics) statics->clear();
	for (size_t b = 0; b < layout.size(); ++b)
	{
		const TBlock& t = layout[b];
		TSlot s;
		s.id = t.id;
		s.object = t.object;
		s.feature = t.feature;
		s.step = t.step;
		switch (t.kind)
		{
			case BlockKind::StaticLandmark:
				s.kind = SlotKind::StaticLandmark;
				if (statics) statics->emplace_back(t.id, b);
				break;
			case BlockKind::ObjectFeature0:
				s.kind = SlotKind::ObjectFeature0;
				break;
			case BlockKind::ObjectFeatureT:
				s.kind = SlotKind::ObjectFeatureT;
				break;
			case BlockKind::ObjectPose:
				s.kind = SlotKind::ObjectPoseA;
				s.id = -1;
				break;
			case BlockKind::ObjectVelocity:
				s.kind = SlotKind::ObjectVelocityA;
				s.id = -1;
				break;
			case BlockKind::OdometryBias:
				s.kind = SlotKind::OdometryBias;
				break;
			case BlockKind::Compressed:
				s.kind = SlotKind::Compressed;
				break;
		}
		slots.push_back(s);
		if (t.kind == BlockKind::ObjectPose && t.dim == 3)
		{
			s.kind = SlotKind::ObjectPoseB;  // [dtheta, pad]
			slots.push_back(s);
		}
		// The velocity's further slots: [omega, pad] (cv, ctrv), [omega, ax], [ay, alpha] (ca).
		for (int i = 1; t.kind == BlockKind::ObjectVelocity && i < t.slots(); ++i)
		{
			s.kind = SlotKind::ObjectVelocityB;
			slots.push_back(s);
		}
	}
}
}  // namespace dynslam::ekf::results
