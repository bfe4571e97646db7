#pragma once
/** @file mrpt_sections.h
 * Checks of the INI sections that MRPT's own classes read: [RangeBearingKFSLAM] and
 * [RangeBearingKFSLAM_KalmanFilter] (mrpt::slam::CRangeBearingKFSLAM2D, the static baseline)
 * and [DynamicKFSLAM_KalmanFilter] (mrpt::bayes::TKF_options of the dynamic EKF). MRPT reads
 * them leniently: a missing key keeps MRPT's default and any other key is ignored, so a
 * misspelled key silently does nothing. The project's own sections reject unknown keys
 * (config_utils.h); for MRPT's sections an unknown key is a warning (MRPT's own INI files, e.g.
 * kf-slam's, may carry keys of other MRPT classes), an error with --strict. */
#include <mrpt/config/CConfigFileBase.h>

#include <string>
#include <vector>

namespace dynslam::apps
{
/** The MRPT-owned sections checked and the keys MRPT 2.5.8 reads in each. */
struct TMrptSection
{
	std::string section;
	std::vector<std::string> keys;
};
const std::vector<TMrptSection>& mrptOwnedSections();

/** One message per key of an MRPT-owned section that MRPT does not read (compared
 * case-insensitively, as MRPT's INI reader does):
 * "[RangeBearingKFSLAM] std_sensor_rang: unknown key (misspelled?), ignored by MRPT". */
std::vector<std::string> unknownMrptKeys(const mrpt::config::CConfigFileBase& ini);

/** The sections an app INI may hold: those dynslam-run, -compare and -montecarlo read
 * ([Run], [Compare], [MonteCarlo], [Backend], [OdometryNoise], [DynamicKFSLAM] and the
 * MRPT-owned ones) and [MappingApplication] (MRPT's kf-slam, whose INI runs as it is). */
const std::vector<std::string>& knownAppSections();

/** One message per section of `ini` that no app reads (compared case-insensitively), with the
 * nearest known name if it is a likely misspelling (at most 2 edits):
 * "section [OdometryNoice] is read by no app (did you mean [OdometryNoise]?), ignored". */
std::vector<std::string> unknownSections(const mrpt::config::CConfigFileBase& ini);

/** Unknown keys of the MRPT-owned sections, then unknown sections. With strict, throws
 * std::invalid_argument("config file 'iniFile': <first message>"); else returns the messages
 * prefixed with the file name, for the caller to log as warnings. */
std::vector<std::string> checkMrptSections(const mrpt::config::CConfigFileBase& ini,
                                           const std::string& iniFile, bool strict);
}  // namespace dynslam::apps
