#include <dynslam/apps/app_common.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/apps/mrpt_sections.h>
#include <dynslam/apps/noise_sources.h>
#include <dynslam/common/config_include.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/eval/writers.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::apps
{
std::vector<std::string> splitList(const std::string& s)
{
	std::vector<std::string> out;
	std::string cur;
	for (char c : s + ",")
		if (c == ',' || c == ' ' || c == '\t')
		{
			if (!cur.empty()) out.push_back(cur);
			cur.clear();
		}
		else
			cur += c;
	return out;
}

void loadIniFile(const std::string& path, mrpt::config::CConfigFileMemory& out)
{
	std::error_code ec;
	if (!std::filesystem::is_regular_file(path, ec))
		throw std::runtime_error("config file '" + path + "' not found");
	config::loadIniWithIncludes(path, out);  // @include (doc/configuration.md)
}

std::vector<std::string> checkSharedSections(const mrpt::config::CConfigFileBase& params,
                                             const std::string& iniFile, bool strict)
{
	TOdometryNoiseOptions().loadFromConfigFile(params, "OdometryNoise");
	return checkMrptSections(params, iniFile, strict);
}

TEvaluation evaluateRun(const io::TGroundTruth& gt, const eval::TRunEstimates& est)
{
	TEvaluation e;
	e.metrics = eval::computeRunMetrics(gt, est);
	e.consistency = eval::computeRunConsistency(gt, est);
	e.summary = eval::summarizeConsistency({e.consistency});
	return e;
}

void setEgoTimes(TFilterRun& run)
{
	for (auto& e : run.est.ego)
		e.t = (e.step >= 0 && size_t(e.step) < run.stamps.size()) ? run.stamps[size_t(e.step)]
		                                                          : eval::kNaN;
}

TDataSettings readDataSettings(const mrpt::config::CConfigFileBase& ini, const std::string& section,
                               const std::string& iniDir)
{
	using namespace dynslam::config;
	TDataSettings s;
	s.rawlog = resolvePath(readString(ini, section, "rawlog", ""), iniDir);
	s.groundTruth = readString(ini, section, "ground_truth", "auto");
	if (s.groundTruth != "auto" && s.groundTruth != "none")
		s.groundTruth = resolvePath(s.groundTruth, iniDir);
	if (s.groundTruth == "none") s.groundTruth.clear();
	s.scenario = readString(ini, section, "scenario", "auto");
	if (s.scenario != "auto") s.scenario = resolvePath(s.scenario, iniDir);
	const int nf = readChoice(ini, section, "noise_from_scenario", {"false", "true", "auto"}, 0);
	s.noiseFromScenario = nf == 0   ? TDataSettings::ScenarioNoise::Off
	                      : nf == 1 ? TDataSettings::ScenarioNoise::On
	                                : TDataSettings::ScenarioNoise::Auto;
	return s;
}

io::TGroundTruth loadGroundTruthForRawlog(const std::string& spec, const TRawlog& rawlog)
{
	if (!isMrptGroundTruthSpec(spec)) return loadGroundTruthFor(spec, rawlog.size(), rawlog.path);
	std::vector<double> times;
	for (size_t k = 0; k < rawlog.size(); ++k)
	{
		const auto o =
		    rawlog.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		times.push_back(o ? mrpt::Clock::toDouble(o->timestamp) : double(k));
	}
	const std::string lm = mrptLandmarksFileFor(spec);
	try
	{
		return io::readMrptGroundTruth(spec, lm, rawlog.framesInFile, rawlog.frameIndex, times);
	}
	catch (const std::exception& e)
	{
		throw std::runtime_error("ground truth '" + spec + "' (MRPT format, landmarks " + lm +
		                         ") for rawlog '" + rawlog.path + "': " + e.what());
	}
}

TLoadedData loadData(const TDataSettings& s, mrpt::config::CConfigFileMemory& params,
                     const std::string& dynSection, const std::string& staticSection)
{
	if (s.rawlog.empty())
		throw std::runtime_error("no rawlog given (command line -r FILE or the INI key rawlog)");
	TLoadedData d;
	TOdometryNoiseOptions odometryNoise;  // used by observations-only (format #2) rawlogs
	odometryNoise.loadFromConfigFile(params, "OdometryNoise");
	d.rawlog = loadRawlog(s.rawlog, odometryNoise);
	std::string gtSpec = s.groundTruth;
	if (gtSpec == "auto") gtSpec = groundTruthBesideRawlog(s.rawlog);
	if (!gtSpec.empty())
	{
		d.gt = loadGroundTruthForRawlog(gtSpec, d.rawlog);
		d.groundTruthUsed =
		    isMrptGroundTruthSpec(gtSpec) ? gtSpec : parseGroundTruthSpec(gtSpec).str();
	}
	if (s.noiseFromScenario != TDataSettings::ScenarioNoise::Off)
	{
		const std::string sc = s.scenario == "auto" ? scenarioBesideRawlog(s.rawlog) : s.scenario;
		std::error_code ec;
		if (s.noiseFromScenario == TDataSettings::ScenarioNoise::On ||
		    std::filesystem::is_regular_file(sc, ec))
		{
			d.noiseUsed =
			    applyScenarioNoise(params, readScenarioNoise(sc), dynSection, staticSection);
			return d;
		}
		d.noiseUsed = "no scenario file " + sc;
	}
	const std::string filled =
	    applyNoiseSources(params, d.rawlog, dynSection, staticSection, s.iniIsShippedDefault);
	if (!filled.empty())
		d.noiseUsed += (d.noiseUsed.empty() ? "" : ": ") + filled;
	else if (!d.noiseUsed.empty())
		d.noiseUsed += ": noise values from the INI";
	return d;
}

eval::TRunConsistency nisOnly(const eval::TRunEstimates& est)
{
	eval::TRunConsistency c;
	for (size_t k = 0; k < est.nis.size() && k < est.nis_dof.size(); ++k)
		if (est.nis_dof[k] > 0) c.nis.samples.push_back({int(k), est.nis[k], est.nis_dof[k]});
	return c;
}

std::string joinPath(const std::string& dir, const std::string& name)
{
	return (std::filesystem::path(dir) / name).string();
}

void writeEstimateFiles(const std::string& dir, const std::string& prefix,
                        const eval::TRunEstimates& est, const io::TGroundTruth* gt,
                        std::vector<std::string>& written)
{
	auto out = [&](const std::string& name, const std::function<void(std::ostream&)>& w)
	{
		const std::string p = joinPath(dir, prefix + name);
		eval::writeFile(p, w);
		written.push_back(p);
	};
	out("ego.csv", [&](std::ostream& os) { eval::writeEgoCsv(os, est, gt); });
	out("trajectory.tum", [&](std::ostream& os) { eval::writeTum(os, est.ego, gt); });
	out("landmarks.csv", [&](std::ostream& os) { eval::writeLandmarksCsv(os, est, gt); });
	if (!est.object_features.empty())
		out("object_features.csv",
		    [&](std::ostream& os) { eval::writeObjectFeaturesCsv(os, est, gt); });
	if (!est.object_poses.empty())
		out("object_poses.csv", [&](std::ostream& os) { eval::writeObjectPosesCsv(os, est, gt); });
	if (std::any_of(est.object_poses.begin(), est.object_poses.end(),
	                [](const auto& p) { return p.velocity.size() > 0; }))
		out("object_motion.csv",
		    [&](std::ostream& os) { eval::writeObjectMotionCsv(os, est, gt); });
}
}  // namespace dynslam::apps
