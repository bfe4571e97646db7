/** @file number_format.cpp */
#include <dynslam/io/number_format.h>

#include <cstdio>
#include <cstdlib>

namespace dynslam::io
{
std::string formatShortest(double v)
{
	char b[40];
	for (int p = 15; p <= 17; ++p)
	{
		std::snprintf(b, sizeof(b), "%.*g", p, v);
		if (std::strtod(b, nullptr) == v) break;
	}
	return b;
}
}  // namespace dynslam::io
