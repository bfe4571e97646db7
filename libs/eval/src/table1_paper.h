#pragma once
/** @file table1_paper.h  (private) The paper's Table I as data. */
#include <array>
#include <string>
#include <vector>

namespace dynslam::eval::detail
{
struct TPaperRow
{
	const char* level;
	const char* quantity;
	std::array<double, 8> values;  ///< NaN = N/A
};
struct TPaperGarbled
{
	const char* level;
	const char* quantity;
	const char* column;
	const char* note;
};
const std::vector<TPaperRow>& paperTable1Rows();
const std::vector<TPaperGarbled>& paperTable1GarbledCells();
}  // namespace dynslam::eval::detail
