#include <dynslam/mrclam/CMrclamOptions.h>
#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <stdexcept>
#include <vector>

namespace dynslam::mrclam
{
namespace
{
[[noreturn]] void fail(const std::string& section, const std::string& key, const std::string& value,
                       const std::string& what)
{
	throw std::invalid_argument("[" + section + "] " + key + " = '" + value + "': " + what);
}

/** Reads a double if the key exists; rejects unparsable, non-finite and below-minimum values. */
void readNum(const mrpt::config::CConfigFileBase& c, const std::string& sec, const std::string& key,
             double& v, double minValue, bool strictlyAbove)
{
	if (!c.keyExists(sec, key)) return;
	const std::string s = c.read_string(sec, key, "", true);
	char* e = nullptr;
	const double x = std::strtod(s.c_str(), &e);
	if (s.empty() || e == s.c_str() ||
	    (*e != '\0' && std::string(e).find_first_not_of(" \t") != std::string::npos))
		fail(sec, key, s, "not a number");
	if (!std::isfinite(x)) fail(sec, key, s, "not finite");
	if (strictlyAbove ? !(x > minValue) : !(x >= minValue))
		fail(sec, key, s,
		     std::string("must be ") + (strictlyAbove ? "> " : ">= ") + std::to_string(minValue));
	v = x;
}

void readFlag(const mrpt::config::CConfigFileBase& c, const std::string& sec,
              const std::string& key, bool& v)
{
	if (!c.keyExists(sec, key)) return;
	std::string s = c.read_string(sec, key, "", true);
	std::transform(s.begin(), s.end(), s.begin(),
	               [](unsigned char ch) { return std::tolower(ch); });
	if (s == "true" || s == "1" || s == "yes")
		v = true;
	else if (s == "false" || s == "0" || s == "no")
		v = false;
	else
		fail(sec, key, s, "not a boolean (true/false)");
}

const std::vector<std::string> kKeys = {"group_window",
                                        "max_range",
                                        "duration",
                                        "clip_to_ground_truth",
                                        "std_range",
                                        "std_bearing",
                                        "odo_delay",
                                        "odo_scale_v",
                                        "odo_scale_w",
                                        "odo_std_xy_min",
                                        "odo_var_xy_per_m",
                                        "odo_var_xy_per_rad",
                                        "odo_std_phi_min",
                                        "odo_var_phi_per_m",
                                        "odo_var_phi_per_rad",
                                        "odo_noise_model",
                                        "odo_tau_xy",
                                        "odo_tau_phi",
                                        "noise_outlier_factor",
                                        "noise_trim_chi2"};
}  // namespace

TMrclamOptions::TMrclamOptions() = default;

void TMrclamOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                        const std::string& sec)
{
	std::vector<std::string> keys;
	c.getAllKeys(sec, keys);
	for (const auto& k : keys)
		if (std::find(kKeys.begin(), kKeys.end(), k) == kKeys.end())
			fail(sec, k, c.read_string(sec, k, ""), "unknown key");
	auto& o = import;
	readNum(c, sec, "group_window", o.group_window, 0, false);
	readNum(c, sec, "max_range", o.max_range, 0, true);
	readNum(c, sec, "duration", o.duration, 0, false);
	readFlag(c, sec, "clip_to_ground_truth", o.clip_to_ground_truth);
	readNum(c, sec, "std_range", o.std_range, 0, true);
	readNum(c, sec, "std_bearing", o.std_bearing, 0, true);
	auto& n = o.odometry_noise;
	if (c.keyExists(sec, "odo_delay"))
	{
		double dl = 0;
		readNum(c, sec, "odo_delay", dl, -10, false);
		if (dl > 10) fail(sec, "odo_delay", c.read_string(sec, "odo_delay", ""), "must be <= 10");
		o.odometry_delay = dl;
	}
	readNum(c, sec, "odo_scale_v", o.odometry_scale_v, 0, true);
	readNum(c, sec, "odo_scale_w", o.odometry_scale_w, 0, true);
	readNum(c, sec, "odo_std_xy_min", n.std_xy_min, 0, false);
	readNum(c, sec, "odo_var_xy_per_m", n.var_xy_per_m, 0, false);
	readNum(c, sec, "odo_var_xy_per_rad", n.var_xy_per_rad, 0, false);
	readNum(c, sec, "odo_std_phi_min", n.std_phi_min, 0, false);
	readNum(c, sec, "odo_var_phi_per_m", n.var_phi_per_m, 0, false);
	readNum(c, sec, "odo_var_phi_per_rad", n.var_phi_per_rad, 0, false);
	if (c.keyExists(sec, "odo_noise_model"))
	{
		const std::string m = c.read_string(sec, "odo_noise_model", "", true);
		if (m == "white")
			n.model = TOdometryNoiseModel::Model::white;
		else if (m == "inflated")
			n.model = TOdometryNoiseModel::Model::inflated;
		else
			fail(sec, "odo_noise_model", m, "must be white or inflated");
	}
	readNum(c, sec, "odo_tau_xy", n.tau_xy, 1, false);
	readNum(c, sec, "odo_tau_phi", n.tau_phi, 1, false);
	readNum(c, sec, "noise_outlier_factor", noise_outlier_factor, 0, true);
	readNum(c, sec, "noise_trim_chi2", noise_trim_chi2, 0, true);
}

void TMrclamOptions::dumpToTextStream(std::ostream& out) const
{
	const auto& o = import;
	const auto& n = o.odometry_noise;
	out << "[MRCLAM_Import]\n"
	    << "group_window = " << o.group_window << "\n"
	    << "max_range = " << o.max_range << "\n"
	    << "duration = " << o.duration << "\n"
	    << "clip_to_ground_truth = " << (o.clip_to_ground_truth ? "true" : "false") << "\n"
	    << "std_range = " << o.std_range << "\n"
	    << "std_bearing = " << o.std_bearing << "\n"
	    << "odo_delay = " << o.odometry_delay << "\n"
	    << "odo_scale_v = " << o.odometry_scale_v << "\n"
	    << "odo_scale_w = " << o.odometry_scale_w << "\n"
	    << "odo_std_xy_min = " << n.std_xy_min << "\n"
	    << "odo_var_xy_per_m = " << n.var_xy_per_m << "\n"
	    << "odo_var_xy_per_rad = " << n.var_xy_per_rad << "\n"
	    << "odo_std_phi_min = " << n.std_phi_min << "\n"
	    << "odo_var_phi_per_m = " << n.var_phi_per_m << "\n"
	    << "odo_var_phi_per_rad = " << n.var_phi_per_rad << "\n"
	    << "odo_noise_model = "
	    << (n.model == TOdometryNoiseModel::Model::inflated ? "inflated" : "white") << "\n"
	    << "odo_tau_xy = " << n.tau_xy << "\n"
	    << "odo_tau_phi = " << n.tau_phi << "\n"
	    << "noise_outlier_factor = " << noise_outlier_factor << "\n"
	    << "noise_trim_chi2 = " << noise_trim_chi2 << "\n";
}
}  // namespace dynslam::mrclam
