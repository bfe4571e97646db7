#include <dynslam/apps/CRunApp.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/apps/noise_sources.h>
#include <dynslam/apps/run_outputs.h>
#include <dynslam/apps/step_timing.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/eval/covariance_writer.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/mode_figure.h>
#include <dynslam/eval/peak_memory.h>
#include <dynslam/eval/writers.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "cmdline.h"

namespace dynslam::apps
{
namespace
{
const char* kRunSection = "Run";
}

CRunApp::CRunApp() : mrpt::system::COutputLogger("dynslam-run") {}

bool CRunApp::initialize(int argc, const char** argv)
{
	TCLAP::CmdLine cmd(
	    "dynslam-run: runs the dynamic EKF-SLAM (or another back-end) on an MRPT rawlog and writes "
	    "estimates, metrics against the ground truth, figures and the effective configuration. "
	    "See doc/apps.md.",
	    ' ', "0.1");
	TCLAP::ValueArg<std::string> argIni(
	    "c", "config", "INI file: [Run] and the back-end's sections (e.g. config/run_highway.ini)",
	    true, "", "file.ini", cmd);
	TCLAP::ValueArg<std::string> argRawlog("r", "rawlog", "Rawlog (overrides [Run] rawlog)", false,
	                                       "", "file.rawlog", cmd);
	TCLAP::ValueArg<std::string> argGt(
	    "", "gt", "Ground truth DIR/BASE (files DIR/BASE_gt_*.csv); overrides [Run] ground_truth",
	    false, "", "DIR/BASE", cmd);
	TCLAP::SwitchArg argNoGt("", "no-gt", "Do not use any ground truth", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "o", "out", "Output directory (created; default [Run] out_dir or dynslam-run-out)", false,
	    "", "dir", cmd);
	TCLAP::ValueArg<std::string> argBackend(
	    "", "backend",
	    "Back-end: ekf | static_all | static_landmarks_only | alg1 | vdo | dynaslam2 | cubeslam | "
	    "clusterslam_decoupled | clusterslam_semidecoupled ([Run] backend)",
	    false, "", "kind", cmd);
	TCLAP::SwitchArg argNoFig("", "no-figures", "Do not draw the PNG figures", cmd);
	TCLAP::SwitchArg argQuiet("q", "quiet", "Only warnings and errors on the console", cmd);
	TCLAP::SwitchArg argCov("", "full-covariance",
	                        "Also write covariance.txt: the ego 3x3 covariance per step, then the "
	                        "landmark and object blocks (format in doc/apps.md)",
	                        cmd);
	TCLAP::ValueArg<std::string> argScene(
	    "", "scene", "Also write the run as an MRPT 3-D scene (open with SceneViewer3D)", false, "",
	    "file.3Dscene", cmd);
	TCLAP::ValueArg<std::string> argVideo("", "video",
	                                      "Also write the run drawn step by step as an MP4 video",
	                                      false, "", "file.mp4", cmd);
	TCLAP::SwitchArg argStrict("", "strict",
	                           "Unknown keys in MRPT's own INI sections ([RangeBearingKFSLAM], "
	                           "[*_KalmanFilter]) are errors, not warnings",
	                           cmd);
	if (!detail::parseCommandLine(cmd, argc, argv, "dynslam-run")) return false;
	fullCovariance = argCov.getValue();
	sceneFile = argScene.getValue();
	videoFile = argVideo.getValue();
	if (argQuiet.getValue()) setMinLoggingLevel(mrpt::system::LVL_WARN);

	iniFile = argIni.getValue();
	loadIniFile(iniFile, params);
	TRunOverrides o;
	o.rawlog = detail::valueIfSet(argRawlog);
	o.gt = detail::valueIfSet(argGt);
	o.backend = detail::valueIfSet(argBackend);
	o.out = detail::valueIfSet(argOut);
	o.noGt = argNoGt.getValue();
	o.noFigures = argNoFig.getValue();
	o.strict = argStrict.getValue();
	readSettings(o);
	// Every output path checked before any input is read; nothing is created until the run is
	// done (a bad input leaves no output folder).
	checkOutputDirUsable(outDir);
	checkOutputFile(sceneFile, "--scene");
	checkOutputFile(videoFile, "--video", videoExtensions());
	return true;
}

void CRunApp::readSettings(const TRunOverrides& o)
{
	try
	{
		using namespace dynslam::config;
		rejectUnknownKeys(params, kRunSection,
		                  {"rawlog", "ground_truth", "scenario", "noise_from_scenario", "backend",
		                   "out_dir", "figures", "progress_every"});
		const TDataSettings d = readDataSettings(params, kRunSection, folderOf(iniFile));
		rawlogFile = o.rawlog ? *o.rawlog : d.rawlog;
		groundTruth = d.groundTruth;
		if (o.rawlog) groundTruth = "auto";  // the INI's ground truth belongs to its rawlog
		if (o.gt) groundTruth = *o.gt;
		if (o.noGt) groundTruth.clear();
		scenarioFile = d.scenario;
		noiseFromScenario = d.noiseFromScenario;
		backend = readString(params, kRunSection, "backend", "ekf");
		if (o.backend) backend = *o.backend;
		outDir = readString(params, kRunSection, "out_dir", outDir);
		if (o.out) outDir = *o.out;
		figures = readBool(params, kRunSection, "figures", true) && !o.noFigures;
		progressEvery = int(readInt(params, kRunSection, "progress_every", 0));
		if (progressEvery < 0)
			fail(kRunSection, "progress_every", std::to_string(progressEvery), "must be >= 0");
		if (rawlogFile.empty())
			throw std::invalid_argument("dynslam-run: no rawlog (give -r FILE or [Run] rawlog in " +
			                            iniFile + ")");
		// Fail early on bad back-end options (before reading a long rawlog).
		for (const auto& w : checkSharedSections(params, iniFile, o.strict)) MRPT_LOG_WARN(w);
		const bool isStatic = backend == "static_all" || backend == "static_landmarks_only";
		mrpt::config::CConfigFileMemory check(params.getContent());  // noise from the data
		fillNoisePlaceholders(check, isStatic ? "" : "DynamicKFSLAM",
		                      isStatic ? "RangeBearingKFSLAM" : "", false);
		makeBackend(backend, check);
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument(inConfigFile(iniFile, e.what()));  // name the INI file
	}
}

void CRunApp::run()
{
	writtenFiles.clear();
	evaluation.reset();
	TDataSettings ds;
	ds.rawlog = rawlogFile;
	ds.groundTruth = groundTruth;
	ds.scenario = scenarioFile;
	ds.noiseFromScenario = noiseFromScenario;
	const bool isStatic = backend == "static_all" || backend == "static_landmarks_only";
	TLoadedData data =
	    loadData(ds, params, isStatic ? "" : "DynamicKFSLAM", isStatic ? "RangeBearingKFSLAM" : "");
	for (const auto& w : data.rawlog.warnings) MRPT_LOG_WARN(w);
	for (const auto& n : data.rawlog.notes) MRPT_LOG_DEBUG(n);
	hasGroundTruth = data.gt.has_value();
	if (hasGroundTruth) gt = *data.gt;
	groundTruthUsed = data.groundTruthUsed;
	scenarioNoiseUsed = data.noiseUsed;
	MRPT_LOG_INFO_STREAM("rawlog "
	                     << rawlogFile << " (" << data.rawlog.size() << " steps), ground truth "
	                     << (hasGroundTruth ? groundTruthUsed : std::string("none")) << ", config "
	                     << iniFile);
	if (!scenarioNoiseUsed.empty()) MRPT_LOG_INFO_STREAM(scenarioNoiseUsed);

	std::ostringstream dump;
	auto filter = makeBackend(backend, params, &dump);
	const size_t n = data.rawlog.size();
	const size_t every = progressEvery > 0 ? size_t(progressEvery) : std::max<size_t>(1, n / 10);
	CTimingCsv timing;  // streamed to a temporary file, moved into outDir after the run
	result = runFilter(
	    *filter, data.rawlog.actions, data.rawlog.frames,
	    [&](size_t done, size_t total)
	    {
		    if (done % every != 0 && done != total) return;
		    MRPT_LOG_INFO_FMT("%s: step %zu/%zu (%3.0f%%)", filter->name().c_str(), done, total,
		                      100.0 * double(done) / double(total));
	    },
	    [&](size_t step, double ms)
	    {
		    TStepTiming t;
		    t.step = step;
		    t.ms = ms;
		    fillStateSize(*filter, t);
		    timing.write(t);
	    });
	setEgoTimes(result);
	if (hasGroundTruth)
		if (const std::string w = timeBaseWarning(result, gt); !w.empty()) MRPT_LOG_WARN(w);
	MRPT_LOG_INFO_FMT("%s: %zu steps in %.1f ms (%.3f ms/step), peak memory %.1f MiB",
	                  result.name.c_str(), result.steps, result.total_ms, result.est.ms_per_step,
	                  eval::peakRssMb());

	makeOutputDir(outDir);
	const io::TGroundTruth* g = hasGroundTruth ? &gt : nullptr;
	writeEstimateFiles(outDir, "", result.est, g, writtenFiles);
	timing.moveTo(joinPath(outDir, "timing.csv"));
	writtenFiles.push_back(joinPath(outDir, "timing.csv"));
	writeOptionalOutputs(data.rawlog);
	writeOutput("effective_config.ini",
	            [&](std::ostream& os)
	            {
		            os << "# Effective configuration of dynslam-run\n# config: " << iniFile
		               << "\n# rawlog: " << rawlogFile
		               << "\n# ground truth: " << (hasGroundTruth ? groundTruthUsed : "none")
		               << "\n";
		            if (!scenarioNoiseUsed.empty()) os << "# " << scenarioNoiseUsed << "\n";
		            os << "\n"
		               << params.getContent() << "\n\n# ---- effective options of the back-end '"
		               << backend << "' (" << result.name << ") ----\n"
		               << dump.str();
	            });

	const eval::TConsistencySummary summary = evaluateAndReport();
	if (figures) drawFigures(summary);
	for (const auto& f : writtenFiles) MRPT_LOG_DEBUG_STREAM("wrote " << f);
	MRPT_LOG_INFO_STREAM("outputs in " << outDir << " (" << writtenFiles.size() << " files)");
}

void CRunApp::writeOutput(const std::string& name, const std::function<void(std::ostream&)>& w)
{
	const std::string p = joinPath(outDir, name);
	eval::writeFile(p, w);
	writtenFiles.push_back(p);
}

eval::TConsistencySummary CRunApp::evaluateAndReport()
{
	eval::TRunConsistency cons;
	eval::TConsistencySummary summary;
	if (hasGroundTruth)
	{
		evaluation = evaluateRun(gt, result.est);
		cons = evaluation->consistency;
		summary = evaluation->summary;
		std::vector<eval::TMetricsRow> rows{
		    {result.name, evaluation->metrics, summary, std::nullopt, std::nullopt,
		     eval::objectVelocityErrors(gt, result.est), std::nullopt, std::nullopt}};
		rows[0].peak_rss_mb = eval::peakRssMb();  // the peak so far: the run is done
		writeOutput("metrics.csv", [&](std::ostream& os) { eval::writeMetricsCsv(os, rows); });
		std::ostringstream table;
		eval::writeMetricsTable(table, rows);
		eval::writeConsistencySummary(table, summary);
		writeOutput("metrics.txt", [&](std::ostream& os) { os << table.str(); });
		writeOutput("nees_ego.csv",
		            [&](std::ostream& os) { eval::writeConsistencyCsv(os, summary.ego); });
		std::cout << table.str();
	}
	else
	{
		cons = nisOnly(result.est);
		summary = eval::summarizeConsistency({cons});
		std::cout << result.name << ": " << result.steps << " steps, " << result.est.ms_per_step
		          << " ms/step (no ground truth: no metrics)\n";
	}
	if (!summary.nis.rows.empty())
		writeOutput("nis.csv",
		            [&](std::ostream& os) { eval::writeConsistencyCsv(os, summary.nis); });
	return summary;
}

void CRunApp::drawFigures(const eval::TConsistencySummary& summary)
{
	const io::TGroundTruth* g = hasGroundTruth ? &gt : nullptr;
	const std::vector<eval::TFigureSeries> series{{result.name, eval::seriesColor(1), &result.est}};
	auto png = [&](const std::string& name, const mrpt::img::CImage& img)
	{
		const std::string p = joinPath(outDir, name);
		eval::savePng(img, p);
		writtenFiles.push_back(p);
	};
	// map.png: equal axes (metres are metres), the image as tall as the content needs (400-1200
	// pixels); a road much longer than wide also gets map_stretched.png (x and y scaled apart).
	eval::TBox box = eval::TBox::empty();
	for (const auto& e : result.est.ego) box.expand(e.mean.x(), e.mean.y());
	if (g)
		for (const auto& x : gt.ego) box.expand(x.x(), x.y());
	const double aspect = box.valid() ? (box.ymax - box.ymin) / (box.xmax - box.xmin) : 1.0;
	eval::TMapFigureOptions mo;
	mo.title = "dynslam-run: " + result.name + " on " + rawlogFile;
	mo.equal_aspect = true;
	mo.height = int(std::clamp(1300.0 * aspect + 100.0, 400.0, 1200.0));
	png("map.png", eval::drawMapFigure(g, series, mo));
	if (aspect < 0.2)
	{
		mo.equal_aspect = false;
		mo.height = 700;
		png("map_stretched.png", eval::drawMapFigure(g, series, mo));
	}
	if (hasGroundTruth)
	{
		png("ego_errors.png", eval::drawEgoErrorFigure(gt, series));
		if (!summary.ego.rows.empty())
			png("nees_ego.png", eval::drawConsistencyFigure(summary.ego));
	}
	if (!summary.nis.rows.empty()) png("nis.png", eval::drawConsistencyFigure(summary.nis));
	if (eval::hasModeProbabilities(result.est))  // object_model = mm
		png("object_modes.png", eval::drawModeFigure(result.est));
}

void CRunApp::writeOptionalOutputs(const TRawlog& rawlog)
{
	const io::TGroundTruth* g = hasGroundTruth ? &gt : nullptr;
	if (fullCovariance)
	{
		const std::string p = joinPath(outDir, "covariance.txt");
		eval::writeFile(p, [&](std::ostream& os) { eval::writeCovariances(os, result.est); });
		writtenFiles.push_back(p);
	}
	const std::vector<TDrawnRun> drawn{{result.name, {0, 0, 255}, &result}};
	if (!sceneFile.empty())
	{
		writeScene(sceneFile, drawn, g);
		writtenFiles.push_back(sceneFile);
	}
	if (!videoFile.empty())
	{
		writeVideo(videoFile, drawn, g, rawlog.frames);
		writtenFiles.push_back(videoFile);
	}
}
}  // namespace dynslam::apps
