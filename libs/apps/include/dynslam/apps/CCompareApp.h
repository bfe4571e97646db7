#pragma once
/** @file CCompareApp.h
 * The dynslam-compare application: on one rawlog, side by side,
 *  (a) static_all: mrpt::slam::CRangeBearingKFSLAM2D unchanged, every feature treated as a
 *      static landmark;
 *  (b) static_landmarks_only: the same filter given only the static landmarks (moving
 *      features removed by ID, dynslam/core/landmark_ids.h);
 *  (c) dynamic: the dynamic EKF (CDynamicKFSLAM2D);
 *  optional rows: dynamic_cv, dynamic_smoothing (other object models), default (the dynamic
 *  EKF with the default profile's keys, doc/configuration.md), dynamic_classified
 *  (feature_labels = classify: no ID oracle; metrics.csv then gains class_precision,
 *  class_recall, class_f1, group_ari against <ground truth>_gt_classes.csv).
 * Prints one table of metrics and timing per filter; with --out DIR writes DIR/metrics.csv
 * (header + one row per filter: filter,ego_rmse_x,ego_rmse_y,ego_rmse_theta,static_rmse_x,
 * static_rmse_y,ate,ms_per_step,...), the per-filter estimate files, overlaid figures and the
 * effective configuration.
 *
 *   dynslam-compare [-c INI] [-r file.rawlog] [--gt DIR/BASE | --no-gt] [--out DIR]
 *                   [--filters static_all,static_landmarks_only,dynamic] [--no-figures] [-q]
 *                   [--full-covariance] [--scene FILE.3Dscene] [--video FILE.mp4]
 *
 * Without -c it uses the shipped highway default config/compare_highway.ini (which points at
 * datasets/highway.rawlog), searched in the current directory, then <exe>/../share/dynslam,
 * then the source tree (data_files.h), and prints which files it used. */
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/estimator/measurement_router.h>
#include <dynslam/eval/class_metrics.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/writers.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/COutputLogger.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dynslam::apps
{
namespace detail
{
struct TMotTruth;  // compare_mot.h (internal)
}
/** The decision about every reading of a run (feature_labels = classify), in rawlog order. */
struct TClassDecisions
{
	std::vector<eval::Decision> decisions;
	/** The estimated object identity of each reading (-1: none): its object, or the object it
	 * continues after a track break (TRoutedReading::identity). */
	std::vector<int64_t> groups;
	std::vector<int> steps;    ///< the step of each reading
	std::vector<int32_t> ids;  ///< the track ID the filter used (-1 readings: as resolved)
	/** The estimator's object of each reading (TRoutedReading::object; -1: static, candidate
	 * or skipped): the numbers of the run's object estimates (eval/object_matching.h). */
	std::vector<int32_t> objects;
	/** The estimator's feature index of each reading within its object (TRoutedReading::feature;
	 * -1 where objects is -1). */
	std::vector<int32_t> features;
	int stepsAdded = 0;  ///< add() calls so far (= the next step)
	/** The router's counts over the run (estimator::TRoutedStep): tracks restarted after a
	 * break (ID reused), split off their object, joined an earlier object; readings held back,
	 * ID -1 readings skipped. */
	size_t restarted = 0, split = 0, joined = 0, held = 0, skipped_unknown_id = 0;
	/** Links of new objects to lost ones (and of those, with two or more candidates), readings
	 * whose hint contradicts their track's, object-steps with contradicting hints
	 * (classify_use_hints, classify_link_gap). */
	size_t linked = 0, link_ambiguous = 0, hint_track_conflicts = 0, hint_group_conflicts = 0;
	void add(const estimator::TRoutedStep& step);
	/** One line of those counts, for the summary under the table. */
	std::string countsLine(const std::string& filter) const;
};

/** With --out and figures: `<filter>_class_map.png` and `<filter>_class_timeline.png`
 * (eval/class_figures.h) of a classifying run, with the class truth `classTruth` if it is given
 * (nullptr: none) and has the run's reading count (else decisions only). Returns the paths
 * written. */
std::vector<std::string> writeClassFigures(const std::string& outDir, const std::string& filter,
                                           const io::TGroundTruth* gt,
                                           const eval::TRunEstimates& est, const TClassDecisions& d,
                                           const std::vector<io::TReadingClass>* classTruth);

class CCompareApp : public mrpt::system::COutputLogger
{
public:
	CCompareApp();
	/** Parses the command line, loads the INI and checks every filter's options. Returns false
	 * for --help / --version. Throws on bad arguments, missing files or bad INI values. */
	bool initialize(int argc, const char** argv);
	/** Runs the filters, prints the table and (with an output dir) writes the files. */
	void run();

	/** Filter names in table order. */
	static const std::vector<std::string>& allFilters();
	/** Title of compare_map.png. */
	static std::string mapTitle(bool withGroundTruth);

	// --- settings (filled by initialize(); may be edited before run()) ---
	mrpt::config::CConfigFileMemory params;
	std::string iniFile;
	TDataSettings data;
	std::vector<std::string> filters = allFilters();
	std::string outDir;  ///< empty: print only
	bool figures = true;
	bool fullCovariance = false;  ///< --full-covariance: DIR/<filter>_covariance.txt
	bool quiet = false;           ///< -q: only the table, warnings and errors on the console
	std::string sceneFile;        ///< --scene FILE.3Dscene (empty: none)
	std::string videoFile;        ///< --video FILE.mp4 (empty: none)
	int progressEvery = 0;  ///< [Compare] progress_every (0: ten lines per filter on long runs)
	/** [Compare] default_profile (relative to the INI's folder; default: the shipped
	 * config/profiles/default.ini, found as the default INI is):
	 * the row `default` is the dynamic EKF on `params` with every key this profile sets in
	 * [DynamicKFSLAM] and in the module sections ([ObjectModel], [OdometryBias], [Classify])
	 * replaced by its value (doc/configuration.md "Profiles"). */
	std::string defaultProfile;
	/** The INI is the shipped default (no -c): without a scenario file its noise values do not
	 * count; the noise then comes from the rawlog's observations (noise_sources.h). */
	bool iniIsShippedDefault = false;

	// --- results of run() ---
	std::vector<TFilterRun> runs;  ///< one per filter that finished, in `filters` order
	/** Filters that diverged (a mean NaN, infinite or beyond 1e9, eval::divergedEstimate: e.g.
	 * MRPT's static filter on KITTI 0007): "<filter>: <reason>". They have no row, no estimates and
	 * no figure line; the other filters run on, the table's footnote and OUT/failed_filters.txt
	 * name them. */
	std::vector<std::string> failedFilters;
	std::map<std::string, TClassDecisions> classDecisions;  ///< of the classifying filters
	/** Metrics per filter; without ground truth the RMS differences of each filter to
	 * referenceFilter (the dynamic filter if it ran, else the first). */
	std::vector<eval::TMetricsRow> rows;
	std::string referenceFilter;  ///< without ground truth: the rows' reference
	bool hasGroundTruth = false;
	/** The scenario's landmark gaps (highway scenarios with landmark_gaps; issue 13): the gap
	 * columns of metrics.csv and compare_ego_error_gap.png. */
	std::vector<std::pair<double, double>> landmarkGaps;
	io::TGroundTruth gt;
	std::string groundTruthUsed, noiseUsed;
	std::string tableText;  ///< the printed table
	/** One line per classifying row on how its object columns were scored (objects matched to
	 * the truth by their readings, or empty without a class ground truth); under the table. */
	std::vector<std::string> objectNotes;
	/** Per classifying row with a class ground truth: its object identities against the true
	 * objects (eval::identityCounts; also a line of objectNotes). */
	std::map<std::string, eval::TIdentityCounts> identities;
	std::vector<std::string> writtenFiles;
	/** How many times run() read <ground truth>_gt_classes.csv (at most once per run). */
	size_t classTruthFilesRead = 0;

private:
	/** What the command line overrides in the INI's [Compare] section. */
	struct TCompareOverrides
	{
		std::optional<std::string> rawlog, gt, filters, out;
		bool noGt = false, noFigures = false, strict = false;
	};
	/** Reads [Compare] and checks every filter's options, with the command line's overrides. */
	void readSettings(const TCompareOverrides& o);
	/** The INI a filter row runs on: `params`, or for `default` params with the default
	 * profile's keys (rebuilt at each call: params may change, noise_from_scenario). */
	const mrpt::config::CConfigFileBase& paramsFor(const std::string& filter,
	                                               const mrpt::config::CConfigFileMemory& base);
	std::unique_ptr<mrpt::config::CConfigFileMemory> m_defaultParams;
	TRawlog m_rawlog;  ///< kept for the snapshot figure
	/** <groundTruthUsed>_gt_classes.csv, read at the first call of classTruth() in a run (the
	 * scores and the figures of every classifying row share it); nullopt: no such file. */
	std::optional<std::vector<io::TReadingClass>> m_classTruth;
	bool m_classTruthRead = false;
	/** The class ground truth of this run's data, read once (nullptr: no file). */
	const std::vector<io::TReadingClass>* classTruth();
	void clearResults();  ///< the results of a previous run(), the class truth read
	/** One filter row of run(): its run, its table row (with ground truth) and its run record;
	 * progress lines every `every` steps (0: start and end only). */
	void runRow(const std::string& f, size_t i, const TLoadedData& d, std::ostream& dump,
	            size_t every);
	/** The box truth for the tracking metrics (compare_mot.h), loaded by run(). */
	std::shared_ptr<const detail::TMotTruth> m_motTruth;
	void writeOutputs(const std::string& optionsDump);
	void drawFigures();
	/** compare_map_start.png: every filter re-run on the first 4 s (ground truth needed). */
	void drawStartSnapshot(const std::vector<eval::TFigureSeries>& series);
	void differenceRows();
	/** The run's header lines (config, rawlog, ground truth, noise); nothing with -q. */
	void printHeader(size_t steps) const;
	void buildTable();          ///< tableText: the rows, the footnote, the diverged filters
	void writeVisualOutputs();  ///< --scene, --video
	/** The object velocity columns of a row (by object number). A classifying row
	 * (classifying != nullptr) is scored against <groundTruthUsed>_gt_classes.csv instead: the
	 * class_* columns, and the object columns with the estimated objects matched to the true
	 * ones by their readings (eval/object_matching.h: obj_* over every matched object, agent_*
	 * RMSE cells against the one with most readings, scoreClassifyingAgents). Without the
	 * file, or with another reading count: those columns empty, a warning and a line in
	 * objectNotes. */
	void scoreObjects(eval::TMetricsRow& row, const TClassDecisions* classifying,
	                  const eval::TRunEstimates& est);
};
}  // namespace dynslam::apps
