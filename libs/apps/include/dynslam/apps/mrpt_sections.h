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

/** With strict, throws std::invalid_argument("config file 'iniFile': <first message>"); else
 * returns the messages prefixed with the file name, for the caller to log as warnings. */
std::vector<std::string> checkMrptSections(const mrpt::config::CConfigFileBase& ini,
                                           const std::string& iniFile, bool strict);
}  // namespace dynslam::apps
