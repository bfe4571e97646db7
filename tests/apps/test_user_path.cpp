/** The MRPT user's path (issue 30) through the real executables: MRPT's unknown landmark ID
 * -1, clean one-line errors, no partial outputs. */
#include <apps_test_utils.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/common/rawlog_file_writer.h>
#include <dynslam/core/landmark_ids.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <set>

using apps_test::configFile;
using apps_test::dataset;
using apps_test::runCommand;

namespace
{
std::string q(const std::string& s) { return "'" + s + "'"; }

/** The highway's frames with every reading of a static landmark after its first sighting
 * given MRPT's unknown landmark ID -1 (count in *unknown). */
std::vector<mrpt::obs::CSensoryFrame::Ptr> withUnknownIds(const dynslam::apps::TRawlog& r,
                                                          size_t* unknown)
{
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	std::set<int32_t> seen;
	*unknown = 0;
	for (const auto& f : r.frames)
	{
		auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
		    *f->getObservationByClass<mrpt::obs::CObservationBearingRange>());
		for (auto& m : obs->sensedData)
			if (dynslam::ids::isStatic(m.landmarkID) && !seen.insert(m.landmarkID).second)
				m.landmarkID = -1, ++*unknown;
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		frames.push_back(sf);
	}
	return frames;
}

/** Writes the highway with unknown IDs (withUnknownIds) to DIR/unknown.rawlog. */
std::string unknownIdRawlog(const std::string& dir)
{
	const auto r = dynslam::apps::loadRawlog(dataset("highway.rawlog"));
	size_t unknown = 0;
	const auto frames = withUnknownIds(r, &unknown);
	const std::string path = dir + "/unknown.rawlog";
	dynslam::CRawlogFileWriter w(path, "test");
	for (size_t k = 0; k < frames.size(); ++k) w.writeStep(*r.actions[k], *frames[k]);
	return path;
}
}  // namespace

TEST(UserPath, UnknownIdsRunInEveryAppByDefault)
{
	// Before issue 30: dynslam-run exited 1 at the first -1 reading ("no known ID range") and
	// dynslam-compare failed in static_all.
	const std::string dir = apps_test::freshDir("u");
	const std::string rawlog = unknownIdRawlog(dir);
	const auto run =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " + q(configFile("run_highway.ini")) +
	               " -r " + q(rawlog) + " --no-gt --no-figures -q -o " + q(dir + "/run"));
	EXPECT_EQ(run.exitCode, 0) << run.output;
	EXPECT_EQ(run.output.find("error"), std::string::npos) << run.output;
	EXPECT_EQ(apps_test::readLines(dir + "/run/ego.csv").size(), 122u);  // header + 121 steps
	const auto cmp = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -r " + q(rawlog) +
	                            " --no-gt --no-figures -q -o " + q(dir + "/cmp"));
	EXPECT_EQ(cmp.exitCode, 0) << cmp.output;
	// -q: the table only (before: the config / rawlog / ground-truth header and "wrote ...").
	EXPECT_EQ(cmp.output.find("dynslam-compare: config"), std::string::npos) << cmp.output;
	EXPECT_EQ(cmp.output.find("wrote "), std::string::npos) << cmp.output;
	EXPECT_NE(cmp.output.find("static_all"), std::string::npos) << cmp.output;
	const auto rows = apps_test::readLines(dir + "/cmp/differences.csv");  // no ground truth
	ASSERT_GE(rows.size(), 4u) << cmp.output;
	EXPECT_EQ(rows[1].rfind("static_all,", 0), 0u) << rows[1];
}

TEST(UserPath, UnknownIdsInABackendWithoutAssociationAreSkippedAndCounted)
{
	// The framework's back-ends have no data association: a -1 reading is skipped and counted,
	// the step (and its odometry) goes on.
	const auto r = dynslam::apps::loadRawlog(dataset("highway.rawlog"));
	size_t unknown = 0;
	const auto frames = withUnknownIds(r, &unknown);
	mrpt::config::CConfigFileMemory ini(apps_test::shippedIniText("run_highway.ini"));
	auto alg1 = dynslam::apps::makeBackend("alg1", ini);
	size_t skipped = 0;
	for (size_t k = 0; k < 6; ++k)
	{
		ASSERT_NO_THROW(alg1->processActionObservation(r.actions[k], frames[k])) << k;
		skipped += alg1->getLastStepReport().skipped_unknown_id;
	}
	size_t expected = 0;
	for (size_t k = 0; k < 6; ++k)
		for (const auto& m :
		     frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>()->sensedData)
			expected += m.landmarkID == -1;
	EXPECT_GT(expected, 0u);
	EXPECT_EQ(skipped, expected);
	EXPECT_GT(alg1->getEgoPose().mean.x(), 20.0);  // 5 increments of ~8 m: odometry kept
}

namespace
{
/** Exit code 1 and exactly one line of output, "<app>: error: ...", with every needle and no
 * exception banner or third-party text. */
void expectOneLineError(const apps_test::TCommandResult& r, const std::string& app,
                        const std::vector<std::string>& needles)
{
	ASSERT_TRUE(r.exitedNormally) << r.output;
	EXPECT_EQ(r.exitCode, 1) << r.output;
	std::string out = r.output;
	while (!out.empty() && out.back() == '\n') out.pop_back();
	EXPECT_EQ(out.find('\n'), std::string::npos) << "more than one line:\n" << r.output;
	EXPECT_EQ(out.rfind(app + ": error: ", 0), 0u) << r.output;
	for (const std::string bad :
	     {"====", "exception", "OpenCV", "PARSE ERROR", "USAGE", ">= 100000"})
		EXPECT_EQ(out.find(bad), std::string::npos) << "'" << bad << "' in: " << r.output;
	for (const auto& n : needles)
		EXPECT_NE(out.find(n), std::string::npos) << "'" << n << "' not in: " << r.output;
}

/** The highway rawlog with reading `m` of frame `k` changed by `edit`, written to DIR/NAME. */
std::string editedRawlog(
    const std::string& dir, const std::string& name, size_t k, size_t m,
    const std::function<void(mrpt::obs::CObservationBearingRange::TMeasurement&)>& edit)
{
	const auto r = dynslam::apps::loadRawlog(dataset("highway.rawlog"));
	const std::string path = dir + "/" + name;
	dynslam::CRawlogFileWriter w(path, "test");
	for (size_t i = 0; i < r.size(); ++i)
	{
		auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
		    *r.frames[i]->getObservationByClass<mrpt::obs::CObservationBearingRange>());
		if (i == k) edit(obs->sensedData.at(m));
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		w.writeStep(*r.actions[i], *sf);
	}
	return path;
}

std::string runCmd(const std::string& exe, const std::string& rawlog, const std::string& out,
                   const std::string& extra = "")
{
	// dynslam-run needs an INI (dynslam-compare has a default one).
	const std::string ini = exe == std::string(DYNSLAM_RUN_EXE)
	                            ? " -c " + q(configFile("run_highway.ini"))
	                            : std::string();
	return q(exe) + ini + " -r " + q(rawlog) + " --no-gt --no-figures -q -o " + q(out) + " " +
	       extra;
}
}  // namespace

TEST(UserPath, BadReadingsAreOneLineAndLeaveNoOutputFolder)
{
	// NaN and negative ranges: rejected when the rawlog is read (before: a "==== non-MRPT
	// exception ====" banner from the filter at step 19); ID 2147483647 by the filter, in
	// words; no output folder in any case.
	const std::string dir = apps_test::freshDir("r");
	const std::string nan =
	    editedRawlog(dir, "nan.rawlog", 19, 2,
	                 [](auto& m) { m.range = std::numeric_limits<float>::quiet_NaN(); });
	const std::string neg = editedRawlog(dir, "neg.rawlog", 19, 2, [](auto& m) { m.range = -3; });
	const std::string big =
	    editedRawlog(dir, "big.rawlog", 19, 2, [](auto& m) { m.landmarkID = 2147483647; });
	for (const std::string exe : {DYNSLAM_RUN_EXE, DYNSLAM_COMPARE_EXE})
	{
		const std::string app = std::filesystem::path(exe).filename().string();
		const auto a = runCommand(runCmd(exe, nan, dir + "/out_nan"));
		expectOneLineError(a, app, {"nan.rawlog': entry", "measurement 2", "not a number"});
		const auto b = runCommand(runCmd(exe, neg, dir + "/out_neg"));
		expectOneLineError(b, app, {"neg.rawlog': entry", "measurement 2", "range is negative"});
		const auto c = runCommand(runCmd(exe, big, dir + "/out_big"));
		expectOneLineError(c, app, {"step 19", "landmark ID 2147483647", "100000..999999999"});
		for (const std::string o : {"/out_nan", "/out_neg", "/out_big"})
			EXPECT_FALSE(std::filesystem::exists(dir + o)) << app << " created " << o;
	}
}

TEST(UserPath, BadOutputPathsFailBeforeTheRunAndLeaveNothing)
{
	// A bad --video / --scene path was found after the run (OpenCV's text), leaving ego.csv,
	// landmarks.csv and trajectory.tum behind.
	const std::string dir = apps_test::freshDir("v");
	apps_test::writeFile(dir + "/afile", "x");
	const std::string rawlog = dataset("highway.rawlog");
	for (const std::string exe : {DYNSLAM_RUN_EXE, DYNSLAM_COMPARE_EXE})
	{
		const std::string app = std::filesystem::path(exe).filename().string();
		const auto a = runCommand(runCmd(exe, rawlog, dir + "/o1", "--video " + q(dir + "/v.txt")));
		expectOneLineError(a, app, {"--video '", "v.txt': unsupported extension '.txt'", ".mp4"});
		const auto b =
		    runCommand(runCmd(exe, rawlog, dir + "/o2", "--video " + q(dir + "/afile/v.mp4")));
		expectOneLineError(b, app, {"--video '", "afile' is a file, not a folder"});
		const auto c =
		    runCommand(runCmd(exe, rawlog, dir + "/o3", "--scene " + q(dir + "/afile/s.3Dscene")));
		expectOneLineError(c, app, {"--scene '", "afile' is a file, not a folder"});
		for (const std::string o : {"/o1", "/o2", "/o3"})
			EXPECT_FALSE(std::filesystem::exists(dir + o)) << app << " created " << o;
	}
	// A good --video path in a folder that does not exist yet: created with the file.
	const auto ok = runCommand(
	    runCmd(DYNSLAM_RUN_EXE, rawlog, dir + "/o4", "--video " + q(dir + "/new/sub/v.mp4")));
	EXPECT_EQ(ok.exitCode, 0) << ok.output;
	EXPECT_TRUE(std::filesystem::exists(dir + "/new/sub/v.mp4"));
}

TEST(UserPath, BadInputFilesLeaveNoOutputFolder)
{
	// Before: the output folder was created by initialize(), before the rawlog was read.
	const std::string dir = apps_test::freshDir("i");
	apps_test::writeFile(dir + "/empty.rawlog", "");
	const std::string full = apps_test::readFile(dataset("highway.rawlog"));
	apps_test::writeFile(dir + "/cut.rawlog", full.substr(0, full.size() / 2));
	std::filesystem::create_directories(dir + "/gt");
	apps_test::writeFile(dir + "/gt/bad_gt_ego.csv", "step,t,x,y,theta\n0,0,abc,0,0\n");
	for (const std::string exe : {DYNSLAM_RUN_EXE, DYNSLAM_COMPARE_EXE})
	{
		const std::string app = std::filesystem::path(exe).filename().string();
		const auto a = runCommand(runCmd(exe, dir + "/empty.rawlog", dir + "/o1"));
		expectOneLineError(a, app, {"empty.rawlog'"});
		const auto b = runCommand(runCmd(exe, dir + "/cut.rawlog", dir + "/o2"));
		expectOneLineError(b, app, {"cut.rawlog': corrupt or truncated"});
		std::string withGt = runCmd(exe, dataset("highway.rawlog"), dir + "/o3");
		withGt.replace(withGt.find(" --no-gt "), 9, " --gt " + q(dir + "/gt/bad") + " ");
		const auto c = runCommand(withGt);
		expectOneLineError(c, app, {"bad"});
		for (const std::string o : {"/o1", "/o2", "/o3"})
			EXPECT_FALSE(std::filesystem::exists(dir + o)) << app << " created " << o;
	}
}

TEST(UserPath, BadCommandLineValueIsOneLineNamingTheArgument)
{
	// Before: TCLAP's "PARSE ERROR" and usage, then "bad command line (see --help)".
	const auto r = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " --runs abc");
	expectOneLineError(r, "dynslam-montecarlo", {"--runs", "'abc' is not a valid value"});
	const auto u = runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " --no-such-flag");
	expectOneLineError(u, "dynslam-run", {"--no-such-flag", "unknown option"});
}
