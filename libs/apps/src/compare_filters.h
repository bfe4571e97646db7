#pragma once
/** @file compare_filters.h
 * (Internal to dynslam-compare.) The filters [Compare] filters may list and their colours. */
#include <string>
#include <vector>

namespace dynslam::apps::detail
{
/** Fixed colours per filter, whatever the subset (an index into eval::seriesColor). */
size_t filterColorIndex(const std::string& name);
/** The filters of a comma-separated list; throws (naming [Compare] filters) on an unknown name
 * or an empty list. */
std::vector<std::string> parseFilterList(const std::string& list);
}  // namespace dynslam::apps::detail
