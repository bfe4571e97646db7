#pragma once
/** @file index_append.h
 * Private to libs/ekf: appends one list of state indices to another (the index lists of blocks
 * handed to the dense helpers, e.g. ekf::marginal). */
#include <vector>

namespace dynslam::ekf
{
inline void appendIndices(std::vector<int>& a, const std::vector<int>& b)
{
	a.insert(a.end(), b.begin(), b.end());
}
}  // namespace dynslam::ekf
