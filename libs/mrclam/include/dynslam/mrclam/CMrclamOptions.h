#pragma once
/** @file CMrclamOptions.h
 * INI options of the MRCLAM importer, section [MRCLAM_Import] (config/mrclam.ini). Every key
 * is optional (the defaults are the Dataset 6 values of config/mrclam.ini); unknown keys and
 * invalid values are rejected with "[MRCLAM_Import] key = 'value': reason". */
#include <dynslam/mrclam/import.h>
#include <mrpt/config/CLoadableOptions.h>

namespace dynslam::mrclam
{
struct TMrclamOptions : public mrpt::config::CLoadableOptions
{
	TMrclamOptions();
	void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
	                        const std::string& section) override;
	void dumpToTextStream(std::ostream& out) const override;

	TImportOptions
	    import;  ///< grouping, window, sensor std written into the rawlog, odometry noise
	double noise_outlier_factor = 5;  ///< --estimate-noise: outlier = |r - median| > f * robust std
	double noise_trim_chi2 = 25;  ///< --estimate-noise: odometry samples trimmed above this NEES
};
}  // namespace dynslam::mrclam
