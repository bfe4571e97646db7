#include <dynslam/estimator/state_layout.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
const char* toString(BlockKind k)
{
	switch (k)
	{
		case BlockKind::StaticLandmark:
			return "static_landmark";
		case BlockKind::ObjectFeature0:
			return "object_feature_t0";
		case BlockKind::ObjectFeatureT:
			return "object_feature_t";
		case BlockKind::ObjectPose:
			return "object_pose";
		case BlockKind::ObjectVelocity:
			return "object_velocity";
		case BlockKind::OdometryBias:
			return "odometry_bias";
		case BlockKind::Compressed:
			return "compressed";
	}
	return "?";
}

void CPaddedLayout::clear()
{
	m_blocks.clear();
	m_first.clear();
	m_blockAtSlot.clear();
	m_nextSeq = 0;
}

void CPaddedLayout::append(const TBlock& b)
{
	TBlock n = b;
	n.seq = m_nextSeq;
	appendNumbered(n);
}

void CPaddedLayout::appendNumbered(const TBlock& b)
{
	if (b.dim < 1 || b.dim > 6)
		throw std::invalid_argument("CPaddedLayout: a block has 1..6 entries, not " +
		                            std::to_string(b.dim));
	m_first.push_back(storageDim());
	for (int s = 0; s < b.slots(); ++s) m_blockAtSlot.push_back(m_blocks.size());
	m_blocks.push_back(b);
	m_nextSeq = std::max(m_nextSeq, b.seq + 1);
}

std::vector<int> CPaddedLayout::indices(size_t b) const
{
	std::vector<int> idx(size_t(m_blocks.at(b).dim));
	for (size_t i = 0; i < idx.size(); ++i) idx[i] = m_first[b] + int(i);
	return idx;
}

std::vector<int> CPaddedLayout::padIndices() const
{
	std::vector<int> out;
	for (size_t b = 0; b < m_blocks.size(); ++b)
		for (int i = m_blocks[b].dim; i < 2 * m_blocks[b].slots(); ++i)
			out.push_back(m_first[b] + i);
	return out;
}

std::vector<int> CPaddedLayout::keptStorage(const std::vector<bool>& remove) const
{
	if (remove.size() != m_blocks.size())
		throw std::invalid_argument("CPaddedLayout::keptStorage: one flag per block");
	std::vector<int> keep;
	keep.reserve(size_t(storageDim()));
	for (int i = 0; i < kEgoDim; ++i) keep.push_back(i);
	for (size_t b = 0; b < m_blocks.size(); ++b)
		if (!remove[b])
			for (int i = 0; i < 2 * m_blocks[b].slots(); ++i) keep.push_back(m_first[b] + i);
	return keep;
}

void CPaddedLayout::removeBlocks(const std::vector<bool>& remove)
{
	if (remove.size() != m_blocks.size())
		throw std::invalid_argument("CPaddedLayout::removeBlocks: one flag per block");
	std::vector<TBlock> kept;
	kept.reserve(m_blocks.size());
	for (size_t b = 0; b < m_blocks.size(); ++b)
		if (!remove[b]) kept.push_back(m_blocks[b]);
	const uint64_t next = m_nextSeq;
	clear();
	for (const auto& b : kept) appendNumbered(b);
	m_nextSeq = next;
}
void CPaddedLayout::convertToObjectFeature0(size_t b, int32_t object, int32_t feature)
{
	TBlock& t = m_blocks.at(b);
	if (t.kind != BlockKind::StaticLandmark)
		throw std::logic_error("CPaddedLayout::convertToObjectFeature0: block " +
		                       std::to_string(b) + " is a " + toString(t.kind) +
		                       ", not a static landmark");
	t.kind = BlockKind::ObjectFeature0;
	t.object = object;
	t.feature = feature;
}

void CPaddedLayout::reassignObjectFeature0(size_t b, int32_t object, int32_t feature)
{
	TBlock& t = m_blocks.at(b);
	if (t.kind != BlockKind::ObjectFeature0)
		throw std::logic_error("CPaddedLayout::reassignObjectFeature0: block " + std::to_string(b) +
		                       " is a " + toString(t.kind) + ", not an object's f_0");
	t.object = object;
	t.feature = feature;
}
}  // namespace dynslam::estimator
