#include "compare_filters.h"

#include <dynslam/apps/app_common.h>
#include <dynslam/common/config_utils.h>

#include <algorithm>

namespace dynslam::apps::detail
{
namespace
{
const char* kCompareFiltersSection = "Compare";

/** Every filter [Compare] filters may list: the default ones, then the dynamic EKF with the
 * other object models (issue 13; makeBackend). */
const std::vector<std::string>& knownFilters()
{
	static const std::vector<std::string> f{
	    "static_all",        "static_landmarks_only", "dynamic",
	    "dynamic_cv",        "dynamic_ctrv",          "dynamic_mm",
	    "dynamic_smoothing", "dynamic_classified",    "default",
	    "odometry",          "tracker_baseline"};
	return f;
}
}  // namespace

/** Fixed colours per filter, whatever the subset: static_all red, static only orange, dynamic
 * blue, dynamic_cv green, dynamic_smoothing purple, dynamic_ctrv and dynamic_classified the
 * sixth and seventh colours, odometry and tracker_baseline 9 and 10 (the palette of 8 wraps:
 * the colours of dynamic and dynamic_cv; eval::seriesColor). */
size_t filterColorIndex(const std::string& n)
{
	return n == "static_all"              ? 0
	       : n == "static_landmarks_only" ? 3
	       : n == "dynamic_cv"            ? 2
	       : n == "dynamic_smoothing"     ? 4
	       : n == "dynamic_ctrv"          ? 5
	       : n == "dynamic_classified"    ? 6
	       : n == "default"               ? 7
	       : n == "dynamic_mm"            ? 8
	       : n == "odometry"              ? 9
	       : n == "tracker_baseline"      ? 10
	                                      : 1;
}

/** The filters of a comma-separated list; throws on an unknown name or an empty list. */
std::vector<std::string> parseFilterList(const std::string& fl)
{
	using dynslam::config::fail;
	const auto& all = knownFilters();
	std::vector<std::string> filters = splitList(fl);
	std::string known;
	for (const auto& k : all) known += (known.empty() ? "" : ", ") + k;
	for (const auto& f : filters)
		if (std::find(all.begin(), all.end(), f) == all.end())
			fail(kCompareFiltersSection, "filters", fl,
			     "unknown filter '" + f + "' (known: " + known + ")");
	if (filters.empty()) fail(kCompareFiltersSection, "filters", fl, "empty list");
	return filters;
}
}  // namespace dynslam::apps::detail
