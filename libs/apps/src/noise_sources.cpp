/** Where the filters' sensor noise comes from without a scenario file (noise_sources.h). */
#include <dynslam/apps/noise_sources.h>
#include <dynslam/common/config_utils.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynslam::apps
{
namespace
{
std::string numText(double v)
{
	std::ostringstream s;
	s.precision(17);
	s << v;
	return s.str();
}

bool has(const mrpt::config::CConfigFileBase& ini, const std::string& s, const std::string& k)
{
	return !ini.read_string(s, k, "").empty();
}

std::string describe(const TObservationNoise& n)
{
	std::ostringstream s;
	s << "sensor_std_range = " << n.std_range << " m, sensor_std_yaw = " << n.std_yaw << " rad";
	return s.str();
}

/** Writes range-bearing noise into [dyn]: measurement_model = range_bearing (a Cartesian
 * Sigma_v cannot come from range-bearing stds; the user's Cartesian model is an error, the
 * shipped default INI's is replaced) and Sigma_v = diag(sr^2, sy^2). */
void writeDynamic(mrpt::config::CConfigFileMemory& ini, const std::string& dyn, double sr,
                  double sy, bool iniIsShippedDefault)
{
	const std::string model = ini.read_string(dyn, "measurement_model", "");
	if (!iniIsShippedDefault && !model.empty() && model != "range_bearing")
		throw std::invalid_argument(
		    "[" + dyn + "] Sigma_v: required key is missing (measurement_model = " + model +
		    "; the sensor stds available are range-bearing: set Sigma_v, or measurement_model = "
		    "range_bearing)");
	ini.write(dyn, "measurement_model", "range_bearing");
	ini.write(dyn, "Sigma_v",
	          config::formatMatrix(Eigen::Vector2d(sr * sr, sy * sy).asDiagonal().toDenseMatrix()));
}
}  // namespace

void fillNoisePlaceholders(mrpt::config::CConfigFileMemory& ini, const std::string& dynSection,
                           const std::string& staticSection, bool iniIsShippedDefault)
{
	if (iniIsShippedDefault) return;  // the shipped INI gives every noise key
	if (!dynSection.empty() && !has(ini, dynSection, "Sigma_v"))
	{
		if (!has(ini, dynSection, "measurement_model"))
			ini.write(dynSection, "measurement_model", "range_bearing");
		ini.write(dynSection, "Sigma_v", "[1 1]");
	}
	if (!staticSection.empty())
		for (const char* k : {"std_sensor_range", "std_sensor_yaw_deg"})
			if (!has(ini, staticSection, k)) ini.write(staticSection, k, "1");
}

std::optional<TObservationNoise> observationNoise(const TRawlog& rawlog, bool* varying)
{
	std::optional<TObservationNoise> first;
	if (varying) *varying = false;
	for (const auto& f : rawlog.frames)
	{
		const auto o = f ? f->getObservationByClass<mrpt::obs::CObservationBearingRange>()
		                 : mrpt::obs::CObservationBearingRange::Ptr();
		if (!o || !(o->sensor_std_range > 0) || !(o->sensor_std_yaw > 0) ||
		    !std::isfinite(o->sensor_std_range) || !std::isfinite(o->sensor_std_yaw))
			continue;
		const TObservationNoise n{o->sensor_std_range, o->sensor_std_yaw};
		if (!first)
			first = n;
		else if (varying && (n.std_range != first->std_range || n.std_yaw != first->std_yaw))
			*varying = true;
	}
	return first;
}

std::string applyNoiseSources(mrpt::config::CConfigFileMemory& ini, const TRawlog& rawlog,
                              const std::string& dynSection, const std::string& staticSection,
                              bool iniIsShippedDefault)
{
	const std::string st = staticSection.empty() ? "RangeBearingKFSLAM" : staticSection;
	const bool iniStatic = !iniIsShippedDefault && has(ini, st, "std_sensor_range") &&
	                       has(ini, st, "std_sensor_yaw_deg");
	const bool needDynamic =
	    !dynSection.empty() && (iniIsShippedDefault || !has(ini, dynSection, "Sigma_v"));
	const bool needStatic = !staticSection.empty() && !iniStatic;
	if (!needDynamic && !needStatic) return "";
	bool varying = false;
	const auto obs = observationNoise(rawlog, &varying);
	std::ostringstream what;
	if (needDynamic && iniStatic)
	{
		const double sr = config::readPositive(ini, st, "std_sensor_range", 0, true);
		const double sy = config::readPositive(ini, st, "std_sensor_yaw_deg", 0, true) * M_PI / 180;
		writeDynamic(ini, dynSection, sr, sy, iniIsShippedDefault);
		what << "[" << dynSection << "] measurement_model = range_bearing, Sigma_v from [" << st
		     << "] std_sensor_range, std_sensor_yaw_deg";
	}
	else if (needDynamic || needStatic)
	{
		if (!obs)
		{
			const std::string sec = needDynamic ? dynSection : st;
			const std::string key = needDynamic ? "Sigma_v" : "std_sensor_range";
			throw std::invalid_argument(
			    "[" + sec + "] " + key + ": " +
			    (iniIsShippedDefault ? std::string("no noise for this rawlog (no -c INI, ")
			                         : std::string("required key is missing (")) +
			    "no scenario file beside the rawlog, and its observations carry no "
			    "sensor_std_range / sensor_std_yaw): give the sensor noise in an INI");
		}
		what << "noise from the rawlog's observations (" << describe(*obs)
		     << (varying ? "; the first of varying values" : "") << "):";
		if (needDynamic)
		{
			writeDynamic(ini, dynSection, obs->std_range, obs->std_yaw, iniIsShippedDefault);
			what << " [" << dynSection << "] measurement_model = range_bearing, Sigma_v";
		}
	}
	if (needStatic && obs)
	{
		ini.write(st, "std_sensor_range", numText(obs->std_range));
		ini.write(st, "std_sensor_yaw_deg", numText(obs->std_yaw * 180 / M_PI));
		if (what.tellp() == 0)
			what << "noise from the rawlog's observations (" << describe(*obs) << "):";
		what << " [" << st << "] std_sensor_range, std_sensor_yaw_deg";
	}
	return what.str();
}
}  // namespace dynslam::apps
