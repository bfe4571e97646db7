#pragma once
/** @file options_sections.h
 * Internal: readers and writers of the scenario INI shared by the TScenarioOptions files. */
#include <dynslam/sim/TScenarioOptions.h>

#include <iosfwd>
#include <string>

namespace mrpt::config
{
class CConfigFileBase;
}

namespace dynslam::sim::detail
{
/** An integer key in [0, maxValue] (throws naming section and key otherwise). */
long readCount(const mrpt::config::CConfigFileBase& c, const std::string& sec,
               const std::string& key, long def, bool required, long maxValue);
/** Reads [Generated] into g (defaults kept for absent optional keys). */
void readGenerated(const mrpt::config::CConfigFileBase& c, TGeneratedOptions& g);
/** Writes the [Generated] section of the effective configuration. */
void dumpGenerated(std::ostream& o, const TGeneratedOptions& g);
}  // namespace dynslam::sim::detail
