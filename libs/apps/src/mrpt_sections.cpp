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

/** Levenshtein distance (insertions, deletions, substitutions). */
size_t editDistance(const std::string& a, const std::string& b)
{
	std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
	for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
	for (size_t i = 1; i <= a.size(); ++i)
	{
		cur[0] = i;
		for (size_t j = 1; j <= b.size(); ++j)
			cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
		std::swap(prev, cur);
	}
	return prev[b.size()];
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

const std::vector<std::string>& knownAppSections()
{
	static const std::vector<std::string> s{"Run",
	                                        "Compare",
	                                        "MonteCarlo",
	                                        "Backend",
	                                        "OdometryNoise",
	                                        "DynamicKFSLAM",
	                                        "DynamicKFSLAM_KalmanFilter",
	                                        "ObjectModel",
	                                        "OdometryBias",
	                                        "Classify",
	                                        "RangeBearingKFSLAM",
	                                        "RangeBearingKFSLAM_KalmanFilter",
	                                        "MappingApplication"};
	return s;
}

std::vector<std::string> unknownSections(const mrpt::config::CConfigFileBase& ini)
{
	std::vector<std::string> sections, out;
	ini.getAllSections(sections);
	for (const auto& s : sections)
	{
		if (s.empty()) continue;  // keys before any section header
		std::string nearest;
		size_t best = 3;
		bool known = false;
		for (const auto& k : knownAppSections())
		{
			const size_t d = editDistance(lower(s), lower(k));
			known = known || d == 0;
			if (d < best) best = d, nearest = k;
		}
		if (known) continue;
		out.push_back("section [" + s + "] is read by no app" +
		              (nearest.empty() ? std::string() : " (did you mean [" + nearest + "]?)") +
		              ", ignored");
	}
	return out;
}

std::vector<std::string> checkMrptSections(const mrpt::config::CConfigFileBase& ini,
                                           const std::string& iniFile, bool strict)
{
	std::vector<std::string> msgs = unknownMrptKeys(ini);
	for (auto& m : unknownSections(ini)) msgs.push_back(std::move(m));
	for (auto& m : msgs) m = "config file '" + iniFile + "': " + m;
	if (strict && !msgs.empty()) throw std::invalid_argument(msgs.front() + " (--strict)");
	return msgs;
}
}  // namespace dynslam::apps
