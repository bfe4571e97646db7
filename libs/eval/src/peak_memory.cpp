#include <dynslam/eval/peak_memory.h>

#include <limits>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/resource.h>
#endif

namespace dynslam::eval
{
double peakRssMb()
{
#if defined(__unix__) || defined(__APPLE__)
	struct rusage u
	{
	};
	if (getrusage(RUSAGE_SELF, &u) != 0) return std::numeric_limits<double>::quiet_NaN();
#if defined(__APPLE__)
	return double(u.ru_maxrss) / (1024.0 * 1024.0);  // bytes on macOS
#else
	return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
#endif
#else
	return std::numeric_limits<double>::quiet_NaN();
#endif
}
}  // namespace dynslam::eval
