#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/apps/noise_sources.h>
#include <dynslam/apps/run_outputs.h>
#include <dynslam/common/config_utils.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/eval/covariance_writer.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/gap_figure.h>
#include <dynslam/eval/gap_metrics.h>
#include <dynslam/eval/mode_figure.h>
#include <dynslam/io/class_ground_truth.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "cmdline.h"
#include "compare_filters.h"
#include "compare_mot.h"

namespace dynslam::apps
{
namespace
{
const char* kCompareSection = "Compare";
const char* kDefaultIni = "config/compare_highway.ini";

/** `dynamic` and `default` (the default profile's keys: paramsFor) are the dynamic EKF. */
std::string backendOf(const std::string& filter)
{
	return filter == "dynamic" || filter == "default" ? "ekf" : filter;
}

/** From this many steps on, each filter logs ten progress lines. */
constexpr size_t kLongRun = 2000;

}  // namespace

const std::vector<std::string>& CCompareApp::allFilters()
{
	static const std::vector<std::string> f{"static_all", "static_landmarks_only", "dynamic"};
	return f;
}

namespace
{
/** The landmark gaps of the data's highway scenario (issue 13); none without a ground truth. */
std::vector<std::pair<double, double>> dataGaps(const TDataSettings& d, bool hasGt)
{
	if (!hasGt) return {};
	return highwayLandmarkGaps(d.scenario == "auto" ? scenarioBesideRawlog(d.rawlog) : d.scenario);
}
}  // namespace

std::string CCompareApp::mapTitle(bool withGroundTruth)
{
	return withGroundTruth ? "Ego paths and maps of the filters over the ground truth"
	                       : "Ego paths and maps of the filters (no ground truth)";
}

CCompareApp::CCompareApp() : mrpt::system::COutputLogger("dynslam-compare") {}

bool CCompareApp::initialize(int argc, const char** argv)
{
	TCLAP::CmdLine cmd(
	    "dynslam-compare: MRPT's static EKF-SLAM (CRangeBearingKFSLAM2D) with all features, the "
	    "same "
	    "filter with static landmarks only, and the dynamic EKF, side by side on one rawlog. "
	    "Without "
	    "arguments: the shipped highway default. See doc/apps.md.",
	    ' ', "0.1");
	TCLAP::ValueArg<std::string> argIni(
	    "c", "config",
	    std::string("INI file ([Compare] and the filters' sections); default ") + kDefaultIni,
	    false, "", "file.ini", cmd);
	TCLAP::ValueArg<std::string> argRawlog("r", "rawlog", "Rawlog (overrides [Compare] rawlog)",
	                                       false, "", "file.rawlog", cmd);
	TCLAP::ValueArg<std::string> argGt("", "gt",
	                                   "Ground truth DIR/BASE (overrides [Compare] ground_truth)",
	                                   false, "", "DIR/BASE", cmd);
	TCLAP::SwitchArg argNoGt("", "no-gt", "Do not use any ground truth", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "o", "out", "Write metrics.csv, estimates and figures into this directory", false, "",
	    "dir", cmd);
	TCLAP::ValueArg<std::string> argFilters(
	    "", "filters", "Comma-separated subset of static_all,static_landmarks_only,dynamic", false,
	    "", "list", cmd);
	TCLAP::SwitchArg argNoFig("", "no-figures", "Do not draw the PNG figures", cmd);
	TCLAP::SwitchArg argQuiet("q", "quiet", "Only the table, warnings and errors", cmd);
	TCLAP::SwitchArg argCov("", "full-covariance",
	                        "With --out: also write <filter>_covariance.txt (ego 3x3 per step, "
	                        "landmark and object blocks; doc/apps.md)",
	                        cmd);
	TCLAP::ValueArg<std::string> argScene(
	    "", "scene", "Also write all filters as an MRPT 3-D scene (open with SceneViewer3D)", false,
	    "", "file.3Dscene", cmd);
	TCLAP::ValueArg<std::string> argVideo(
	    "", "video", "Also write the filters drawn step by step as an MP4 video", false, "",
	    "file.mp4", cmd);
	TCLAP::SwitchArg argStrict("", "strict",
	                           "Unknown keys in MRPT's own INI sections ([RangeBearingKFSLAM], "
	                           "[*_KalmanFilter]) are errors, not warnings",
	                           cmd);
	if (!detail::parseCommandLine(cmd, argc, argv, "dynslam-compare")) return false;
	fullCovariance = argCov.getValue();
	sceneFile = argScene.getValue();
	videoFile = argVideo.getValue();
	quiet = argQuiet.getValue();
	if (quiet) setMinLoggingLevel(mrpt::system::LVL_WARN);

	iniFile = argIni.isSet() ? argIni.getValue() : locateShippedFile(kDefaultIni);
	iniIsShippedDefault = !argIni.isSet();
	loadIniFile(iniFile, params);
	TCompareOverrides o;
	o.rawlog = detail::valueIfSet(argRawlog);
	o.gt = detail::valueIfSet(argGt);
	o.filters = detail::valueIfSet(argFilters);
	o.out = detail::valueIfSet(argOut);
	o.noGt = argNoGt.getValue();
	o.noFigures = argNoFig.getValue();
	o.strict = argStrict.getValue();
	readSettings(o);
	// Every output path checked before any input is read; nothing is created until the run is
	// done (a bad input leaves no output folder).
	if (!outDir.empty()) checkOutputDirUsable(outDir);
	checkOutputFile(sceneFile, "--scene");
	checkOutputFile(videoFile, "--video", videoExtensions());
	return true;
}

void CCompareApp::readSettings(const TCompareOverrides& o)
{
	try
	{
		using namespace dynslam::config;
		rejectUnknownKeys(params, kCompareSection,
		                  {"rawlog", "ground_truth", "scenario", "noise_from_scenario", "filters",
		                   "figures", "out_dir", "progress_every", "default_profile"});
		const std::string profile = readString(params, kCompareSection, "default_profile", "");
		defaultProfile = profile.empty() ? locateShippedFile("config/profiles/default.ini")
		                                 : resolvePath(profile, folderOf(iniFile));
		data = readDataSettings(params, kCompareSection, folderOf(iniFile));
		if (o.rawlog)
		{
			// The INI's ground truth belongs to its rawlog: look beside the new one instead.
			data.rawlog = *o.rawlog;
			data.groundTruth = "auto";
		}
		if (o.gt) data.groundTruth = *o.gt;
		if (o.noGt) data.groundTruth.clear();
		if (data.rawlog.empty())
			throw std::invalid_argument(
			    "dynslam-compare: no rawlog (give -r FILE or [Compare] rawlog in " + iniFile + ")");

		const std::string fl =
		    o.filters ? *o.filters : readString(params, kCompareSection, "filters", "");
		if (!fl.empty()) filters = detail::parseFilterList(fl);
		figures = readBool(params, kCompareSection, "figures", true) && !o.noFigures;
		progressEvery = int(readInt(params, kCompareSection, "progress_every", 0));
		if (progressEvery < 0)
			fail(kCompareSection, "progress_every", std::to_string(progressEvery), "must be >= 0");
		outDir = readString(params, kCompareSection, "out_dir", "");
		if (o.out) outDir = *o.out;
		if (fullCovariance && outDir.empty())
			throw std::invalid_argument("--full-covariance needs --out DIR (the files go there)");
		for (const auto& w : checkSharedSections(params, iniFile, o.strict)) MRPT_LOG_WARN(w);
		data.iniIsShippedDefault = iniIsShippedDefault;
		// Fail early on bad options; noise that will come from the data has a placeholder.
		mrpt::config::CConfigFileMemory check(params.getContent());
		fillNoisePlaceholders(check, "DynamicKFSLAM", "RangeBearingKFSLAM", iniIsShippedDefault);
		for (const auto& f : filters) makeBackend(backendOf(f), paramsFor(f, check));
	}
	catch (const std::invalid_argument& e)
	{
		throw std::invalid_argument(inConfigFile(iniFile, e.what()));  // name the INI file
	}
}

void CCompareApp::run()
{
	clearResults();
	TLoadedData d = loadData(data, params, "DynamicKFSLAM", "RangeBearingKFSLAM");
	for (const auto& w : d.rawlog.warnings) MRPT_LOG_WARN(w);
	for (const auto& n : d.rawlog.notes) MRPT_LOG_DEBUG(n);
	hasGroundTruth = d.gt.has_value();
	if (hasGroundTruth) gt = *d.gt;
	groundTruthUsed = d.groundTruthUsed;
	noiseUsed = d.noiseUsed;
	m_rawlog = d.rawlog;
	printHeader(d.rawlog.size());
	landmarkGaps = dataGaps(data, hasGroundTruth);
	std::ostringstream dump;
	const size_t n = d.rawlog.size();
	// Progress lines on long runs: every progress_every steps, or ten per filter from
	// kLongRun steps on (a filter's start and end are always logged).
	const size_t every = progressEvery > 0 ? size_t(progressEvery)
	                     : n >= kLongRun   ? std::max<size_t>(1, n / 10)
	                                       : 0;
	m_motTruth.reset();
	if (hasGroundTruth && !isMrptGroundTruthSpec(groundTruthUsed))
		m_motTruth =
		    std::make_shared<const detail::TMotTruth>(detail::loadMotTruth(groundTruthUsed, gt));
	for (size_t i = 0; i < filters.size(); ++i) runRow(filters[i], i, d, dump, every);
	if (runs.empty())
		throw std::runtime_error("dynslam-compare: every filter diverged (" +
		                         failedFilters.front() + ", ...)");
	if (!hasGroundTruth) differenceRows();

	buildTable();
	std::cout << (quiet ? "" : "\n") << tableText;
	if (!outDir.empty())
		writeOutputs(dump.str());
	else if (!quiet)
		std::cout << "(add --out DIR to write metrics.csv, per-filter estimates and figures)\n";
	writeVisualOutputs();
}

void CCompareApp::runRow(const std::string& f, size_t i, const TLoadedData& d, std::ostream& dump,
                         size_t every)
{
	const size_t n = d.rawlog.size();
	dump << "\n# ======== filter " << f << " ========\n";
	auto backend = makeBackend(backendOf(f), paramsFor(f, params), &dump);
	MRPT_LOG_INFO_FMT("filter %zu/%zu: %s on %zu steps", i + 1, filters.size(), f.c_str(), n);
	// feature_labels = classify: the decision about every reading, for the class metrics.
	const auto* ekf = dynamic_cast<const CDynamicKFSLAM2D*>(backend.get());
	const bool classifies =
	    ekf && estimator::routers().caps(ekf->options.feature_labels).classifies;
	TClassDecisions decisions;
	std::vector<std::vector<TTrackedBox>> boxes;  // the tracking metrics (issue 31)
	bool tracks = false;
	TFilterRun r = runFilter(*backend, d.rawlog.actions, d.rawlog.frames,
	                         [&](size_t done, size_t total)
	                         {
		                         if (classifies) decisions.add(ekf->lastRoutedStep());
		                         boxes.push_back(backend->trackedBoxes());
		                         tracks = tracks || !boxes.back().empty();
		                         if (every == 0 || (done % every != 0 && done != total)) return;
		                         MRPT_LOG_INFO_FMT("%s: step %zu/%zu (%3.0f%%)", f.c_str(), done,
		                                           total, 100.0 * double(done) / double(total));
	                         });
	r.name = f;
	if (const std::string bad = eval::divergedEstimate(r.est); !bad.empty())
	{
		failedFilters.push_back(f + ": diverged (" + bad + " non-finite or beyond 1e9)");
		MRPT_LOG_ERROR_FMT("%s: left out of the table", failedFilters.back().c_str());
		return;
	}
	setEgoTimes(r);
	if (hasGroundTruth && runs.empty())
		if (const std::string w = timeBaseWarning(r, gt); !w.empty()) MRPT_LOG_WARN(w);
	MRPT_LOG_INFO_FMT("%s: %zu steps, %.3f ms/step", f.c_str(), r.steps, r.est.ms_per_step);
	if (hasGroundTruth)
	{
		const TEvaluation ev = evaluateRun(gt, r.est);
		rows.push_back({f, ev.metrics, ev.summary, std::nullopt, std::nullopt, std::nullopt,
		                std::nullopt, std::nullopt});
		if (!landmarkGaps.empty()) rows.back().gap = eval::gapMetrics(gt, r.est.ego, landmarkGaps);
		scoreObjects(rows.back(), classifies ? &decisions : nullptr, r.est);
		if (tracks && m_motTruth && m_motTruth->valid)
			rows.back().mot = detail::scoreMot(*m_motTruth, boxes);
	}
	if (classifies) classDecisions[f] = decisions;
	runs.push_back(std::move(r));
}

void CCompareApp::buildTable()
{
	std::ostringstream table;
	eval::writeMetricsTable(table, rows);
	if (hasGroundTruth)
		table << "RMSE against the ground truth (map: static landmarks only); ms/step: wall time "
		         "of one filter step on this machine.\n";
	else
		table << "No ground truth: RMS DIFFERENCES to the '" << referenceFilter
		      << "' row, not errors (ego per step; map: the static landmarks both filters have; "
		         "ATE column: RMS ego position distance); ms/step: wall time of one filter step "
		         "on this machine.\n";
	for (const auto& [f, d] : classDecisions) table << d.countsLine(f);
	for (const auto& r : rows)
		if (r.mot) table << detail::motLine(r.filter, *r.mot) << "\n";
	for (const auto& n : objectNotes) table << n << "\n";
	for (const auto& fail : failedFilters) table << "NOT IN THE TABLE: " << fail << "\n";
	tableText = table.str();
}

void CCompareApp::differenceRows()
{
	// The reference: the dynamic filter if it ran, else the first filter.
	size_t ref = 0;
	for (size_t i = 0; i < runs.size(); ++i)
		if (runs[i].name == "dynamic") ref = i;
	referenceFilter = runs.empty() ? std::string() : runs[ref].name;
	const io::TGroundTruth refGt =
	    runs.empty() ? io::TGroundTruth() : estimatesAsReference(runs[ref]);
	for (const auto& r : runs)
	{
		eval::TMetricsRow row;
		row.filter = r.name;
		row.metrics = eval::computeRunMetrics(refGt, r.est);
		rows.push_back(row);
	}
}

void CCompareApp::writeVisualOutputs()
{
	std::vector<TDrawnRun> drawn;
	for (const auto& r : runs)
	{
		const auto c = eval::seriesColor(detail::filterColorIndex(r.name));
		drawn.push_back({r.name, {c.R, c.G, c.B}, &r});
	}
	const io::TGroundTruth* g = hasGroundTruth ? &gt : nullptr;
	if (!sceneFile.empty())
	{
		writeScene(sceneFile, drawn, g);
		writtenFiles.push_back(sceneFile);
	}
	if (!videoFile.empty())
	{
		// Readings drawn from the last filter's pose (the dynamic EKF by default).
		std::reverse(drawn.begin(), drawn.end());
		writeVideo(videoFile, drawn, g, m_rawlog.frames);
		writtenFiles.push_back(videoFile);
	}
}

void CCompareApp::writeOutputs(const std::string& optionsDump)
{
	makeOutputDir(outDir);
	const io::TGroundTruth* g = hasGroundTruth ? &gt : nullptr;
	auto out = [&](const std::string& name, const std::function<void(std::ostream&)>& w)
	{
		const std::string p = joinPath(outDir, name);
		eval::writeFile(p, w);
		writtenFiles.push_back(p);
	};
	// Without ground truth the rows are differences to the reference filter, not errors.
	out(hasGroundTruth ? "metrics.csv" : "differences.csv",
	    [&](std::ostream& os) { eval::writeMetricsCsv(os, rows); });
	out("metrics.txt",
	    [&](std::ostream& os)
	    {
		    os << tableText;
		    for (const auto& r : rows)
			    if (r.consistency)
			    {
				    os << "\n" << r.filter << ": ";
				    eval::writeConsistencySummary(os, *r.consistency);
			    }
	    });
	if (!failedFilters.empty())
		out("failed_filters.txt",
		    [&](std::ostream& os)
		    {
			    for (const auto& fail : failedFilters) os << fail << "\n";
		    });
	for (const auto& r : runs)
	{
		writeEstimateFiles(outDir, r.name + "_", r.est, g, writtenFiles);
		if (fullCovariance)
			out(r.name + "_covariance.txt",
			    [&](std::ostream& os) { eval::writeCovariances(os, r.est); });
	}
	out("effective_config.ini",
	    [&](std::ostream& os)
	    {
		    os << "# Effective configuration of dynslam-compare\n# config: " << iniFile
		       << "\n# rawlog: " << data.rawlog
		       << "\n# ground truth: " << (g ? groundTruthUsed : "none") << "\n";
		    if (!noiseUsed.empty()) os << "# " << noiseUsed << "\n";
		    os << "\n"
		       << params.getContent() << "\n\n# ---- effective options of every filter ----\n"
		       << optionsDump;
	    });
	if (figures) drawFigures();
	if (!quiet) std::cout << "wrote " << writtenFiles.size() << " files into " << outDir << "\n";
}

void CCompareApp::drawFigures()
{
	const io::TGroundTruth* g = hasGroundTruth ? &gt : nullptr;
	std::vector<eval::TFigureSeries> series;
	for (size_t i = 0; i < runs.size(); ++i)
	{
		// fixed colours per filter, whatever the subset: static_all red, static only orange,
		// dynamic blue
		series.push_back({runs[i].name, eval::seriesColor(detail::filterColorIndex(runs[i].name)),
		                  &runs[i].est});
	}
	auto png = [&](const std::string& name, const mrpt::img::CImage& img)
	{
		const std::string p = joinPath(outDir, name);
		eval::savePng(img, p);
		writtenFiles.push_back(p);
	};
	// The whole run, framed on the ground truth: a diverging filter leaves the frame (its path
	// is clipped) instead of shrinking everything else to a dot.
	eval::TBox truthBox = eval::TBox::empty();
	if (g)
	{
		for (const auto& x : gt.ego) truthBox.expand(x.x(), x.y());
		for (const auto& [id, p] : gt.landmarks) truthBox.expand(p.x(), p.y());
	}
	eval::TMapFigureOptions mo;
	mo.title = mapTitle(hasGroundTruth);
	if (g && truthBox.valid()) mo.view = truthBox.withMargin(0.03);
	png("compare_map.png", eval::drawMapFigure(g, series, mo));
	for (const auto& r : runs)
		if (const auto it = classDecisions.find(r.name); it != classDecisions.end())
			for (const auto& p :
			     writeClassFigures(outDir, r.name, g, r.est, it->second, classTruth()))
				writtenFiles.push_back(p);
	for (const auto& r : runs)  // object_model = mm
		if (eval::hasModeProbabilities(r.est))
			png(r.name + "_object_modes.png", eval::drawModeFigure(r.est));
	if (!hasGroundTruth) return;
	png("compare_ego_errors.png", eval::drawEgoErrorFigure(gt, series));
	if (!landmarkGaps.empty())
		png("compare_ego_error_gap.png", eval::drawGapErrorFigure(gt, series, landmarkGaps));
	std::vector<eval::TFigureSeries> good;
	for (const auto& s : series)
		if (s.name != "static_all") good.push_back(s);
	if (!good.empty() && good.size() < series.size())
	{
		eval::TErrorFigureOptions eo;
		eo.title = "Ego pose error without static_all";
		png("compare_ego_errors_without_static_all.png", eval::drawEgoErrorFigure(gt, good, eo));
	}

	drawStartSnapshot(series);
}

void CCompareApp::drawStartSnapshot(const std::vector<eval::TFigureSeries>& series)
{
	// Snapshot after the first seconds, when the moving features start to drag the static
	// filter: every filter re-run on the first steps only, drawn with equal aspect.
	const double snapSeconds = 4.0;
	size_t K = 0;
	while (K + 1 < gt.numSteps() && K + 1 < m_rawlog.size() &&
	       gt.t[K + 1] - gt.t.front() <= snapSeconds)
		++K;
	const std::vector<mrpt::obs::CActionCollection::Ptr> acts(
	    m_rawlog.actions.begin(), m_rawlog.actions.begin() + long(K + 1));
	const std::vector<mrpt::obs::CSensoryFrame::Ptr> sfs(m_rawlog.frames.begin(),
	                                                     m_rawlog.frames.begin() + long(K + 1));
	std::vector<TFilterRun> snaps;
	snaps.reserve(runs.size());
	for (const auto& r : runs)
	{
		auto b = makeBackend(backendOf(r.name), paramsFor(r.name, params));
		snaps.push_back(runFilter(*b, acts, sfs));
		snaps.back().name = r.name;
	}
	std::vector<eval::TFigureSeries> snapSeries = series;
	for (size_t i = 0; i < snaps.size(); ++i) snapSeries[i].est = &snaps[i].est;
	eval::TBox box = eval::TBox::empty();
	for (size_t k = 0; k <= K && k < gt.numSteps(); ++k) box.expand(gt.ego[k].x(), gt.ego[k].y());
	box.xmin -= 40;
	box.xmax += 60;
	box.ymin = std::min(box.ymin, -30.0) - 8;
	box.ymax = std::max(box.ymax, 30.0) + 8;
	eval::TMapFigureOptions zo;
	zo.view = box;
	zo.equal_aspect = true;
	std::ostringstream t;
	t << "Estimates at step " << K << " (t = " << gt.t[K] - gt.t.front()
	  << " s): ego paths and maps so far, 3-sigma ellipses";
	zo.title = t.str();
	const std::string p = joinPath(outDir, "compare_map_start.png");
	eval::savePng(eval::drawMapFigure(&gt, snapSeries, zo), p);
	writtenFiles.push_back(p);
}

}  // namespace dynslam::apps
