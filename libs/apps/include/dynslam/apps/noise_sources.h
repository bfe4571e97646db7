#pragma once
/** @file noise_sources.h
 * Where the filters' sensor noise comes from when no scenario file gives it (issue 30 item 2,
 * doc/apps.md "Where the noise comes from"), in this order:
 *  1. the INI, if it gives it ([DynamicKFSLAM] Sigma_v; [RangeBearingKFSLAM] std_sensor_range
 *     and std_sensor_yaw_deg), unless the INI is the app's shipped default (dynslam-compare
 *     without -c: its values are the highway's, not the user's);
 *  2. for [DynamicKFSLAM] without Sigma_v: [RangeBearingKFSLAM]'s sensor stds (MRPT's kf-slam
 *     INI as it is), as measurement_model = range_bearing;
 *  3. the rawlog's own CObservationBearingRange::sensor_std_range / sensor_std_yaw (MRPT's
 *     fields, set by its simulator), as measurement_model = range_bearing;
 *  4. else a clear error naming the section and key. */
#include <dynslam/apps/rawlog_io.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <optional>
#include <string>

namespace dynslam::apps
{
/** The sensor stds the rawlog's observations carry: those of the first observation with both
 * positive, in [m] and [rad]; nullopt if none has them. `varying` (if given) is set if another
 * observation carries different positive values. */
struct TObservationNoise
{
	double std_range = 0;
	double std_yaw = 0;  ///< [rad]
};
std::optional<TObservationNoise> observationNoise(const TRawlog& rawlog, bool* varying = nullptr);

/** Fills the missing noise of `dynSection` and `staticSection` (either may be empty: not run)
 * by the rules of the file comment. `iniIsShippedDefault`: the INI's own noise does not count.
 * Returns a one-line description of what was written ("" if nothing); throws
 * std::invalid_argument naming section and key if a filter is left without noise. */
std::string applyNoiseSources(mrpt::config::CConfigFileMemory& ini, const TRawlog& rawlog,
                              const std::string& dynSection, const std::string& staticSection,
                              bool iniIsShippedDefault);
/** For checking a filter's other options before the rawlog is read: writes a placeholder noise
 * (measurement_model = range_bearing, Sigma_v = I; std_sensor_* = 1) where applyNoiseSources()
 * will fill it in from the data. */
void fillNoisePlaceholders(mrpt::config::CConfigFileMemory& ini, const std::string& dynSection,
                           const std::string& staticSection, bool iniIsShippedDefault);
}  // namespace dynslam::apps
