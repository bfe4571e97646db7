#include <dynslam/apps/mrpt_sections.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
std::string lower(std::string s)
{
	std::transform(s.begin(), s.end(), s.begin(),
	               [](unsigned char c) { return char(std::tolower(c)); });
	return s;
}
}  // namespace

const std::vector<TMrptSection>& mrptOwnedSections()
{
	// MRPT 2.5.8: CRangeBearingKFSLAM2D::TOptions::loadFromConfigFile and
	// TKF_options::loadFromConfigFile (CKalmanFilterCapable.h).
	static const std::vector<std::string> kf{"method",
	                                         "verbosity_level",
	                                         "IKF_iterations",
	                                         "enable_profiler",
	                                         "use_analytic_transition_jacobian",
	                                         "use_analytic_observation_jacobian",
	                                         "debug_verify_analytic_jacobians",
	                                         "debug_verify_analytic_jacobians_threshold"};
	static const std::vector<TMrptSection> s{
	    {"RangeBearingKFSLAM",
	     {"stds_Q_no_odo", "std_sensor_range", "std_sensor_yaw_deg", "quantiles_3D_representation",
	      "create_simplemap", "data_assoc_method", "data_assoc_metric", "data_assoc_IC_metric",
	      "data_assoc_IC_chi2_thres", "data_assoc_IC_ml_threshold"}},
	    {"RangeBearingKFSLAM_KalmanFilter", kf},
	    {"DynamicKFSLAM_KalmanFilter", kf}};
	return s;
}

std::vector<std::string> unknownMrptKeys(const mrpt::config::CConfigFileBase& ini)
{
	std::vector<std::string> out;
	for (const auto& sec : mrptOwnedSections())
	{
		std::vector<std::string> keys;
		ini.getAllKeys(sec.section, keys);
		for (const auto& k : keys)
		{
			const bool known =
			    std::any_of(sec.keys.begin(), sec.keys.end(),
			                [&](const std::string& m) { return lower(m) == lower(k); });
			if (!known)
				out.push_back("[" + sec.section + "] " + k +
				              ": unknown key (misspelled?), ignored by MRPT");
		}
	}
	return out;
}

std::vector<std::string> checkMrptSections(const mrpt::config::CConfigFileBase& ini,
                                           const std::string& iniFile, bool strict)
{
	std::vector<std::string> msgs = unknownMrptKeys(ini);
	for (auto& m : msgs) m = "config file '" + iniFile + "': " + m;
	if (strict && !msgs.empty()) throw std::invalid_argument(msgs.front() + " (--strict)");
	return msgs;
}
}  // namespace dynslam::apps
