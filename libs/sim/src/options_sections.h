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
/** Reads [ObjectMotion] into o.object_motion (after [Noise]: checks object_accel_psd). */
void readObjectMotion(const mrpt::config::CConfigFileBase& c, TScenarioOptions& o);
/** Writes [ObjectMotion] when model = markov (nothing otherwise). */
void dumpObjectMotion(std::ostream& o, const TObjectMotionOptions& m);
}  // namespace dynslam::sim::detail
