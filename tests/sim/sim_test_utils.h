#pragma once
/** Helpers shared by the simulator tests. */
#include <dynslam/sim/TScenarioOptions.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace dynslam_test
{
inline std::string readFile(const std::string& path)
{
	std::ifstream f(path, std::ios::binary);
	std::stringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

inline std::string highwayIni() { return std::string(DYNSLAM_CONFIG_DIR) + "/highway.ini"; }

inline dynslam::sim::TScenarioOptions highwayOptions()
{
	return dynslam::sim::loadScenario(highwayIni());
}

/** Two-sided (1 - alpha) interval of a chi-square variable with `dof` degrees of freedom
 * (Wilson-Hilferty; z = standard normal quantile of 1 - alpha/2, 3.2905 for alpha = 0.001). */
inline std::pair<double, double> chi2Interval(double dof, double z = 3.2905)
{
	const double a = 2.0 / (9.0 * dof);
	return {dof * std::pow(1 - a - z * std::sqrt(a), 3),
	        dof * std::pow(1 - a + z * std::sqrt(a), 3)};
}

/** Replaces (or adds) `key = value` in [section] of an INI text. */
inline std::string setIniKey(const std::string& ini, const std::string& section,
                             const std::string& key, const std::string& value)
{
	std::istringstream in(ini);
	std::ostringstream out;
	std::string line, cur;
	bool done = false;
	while (std::getline(in, line))
	{
		std::string t = line;
		t.erase(0, t.find_first_not_of(" \t"));
		if (!t.empty() && t[0] == '[')
		{
			if (cur == section && !done)
			{
				out << key << " = " << value << "\n";
				done = true;
			}
			cur = t.substr(1, t.find(']') - 1);
		}
		else if (cur == section && t.rfind(key, 0) == 0)
		{
			const std::string rest = t.substr(key.size());
			const auto p = rest.find_first_not_of(" \t");
			if (p != std::string::npos && rest[p] == '=')
			{
				if (!done) out << key << " = " << value << "\n";
				done = true;
				continue;
			}
		}
		out << line << "\n";
	}
	if (!done)
	{
		if (cur != section) out << "[" << section << "]\n";
		out << key << " = " << value << "\n";
	}
	return out.str();
}

/** Removes `key` from [section]. */
inline std::string removeIniKey(const std::string& ini, const std::string& section,
                                const std::string& key)
{
	std::istringstream in(ini);
	std::ostringstream out;
	std::string line, cur;
	while (std::getline(in, line))
	{
		std::string t = line;
		t.erase(0, t.find_first_not_of(" \t"));
		if (!t.empty() && t[0] == '[')
			cur = t.substr(1, t.find(']') - 1);
		else if (cur == section && t.rfind(key, 0) == 0)
		{
			const std::string rest = t.substr(key.size());
			const auto p = rest.find_first_not_of(" \t");
			if (p != std::string::npos && rest[p] == '=') continue;
		}
		out << line << "\n";
	}
	return out.str();
}
}  // namespace dynslam_test
