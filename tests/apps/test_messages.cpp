/** Messages of the executables (issue 16, item 10): one "<program>: error: " prefix, no MRPT
 * "non-MRPT exception" banner, a sentence for an output folder that cannot be created,
 * --help exits 0, no '\r' progress bar in a redirected log, a progress line per filter in
 * dynslam-compare. Each case runs the real executable with stdout+stderr captured to a file
 * (so not a terminal). */
#include <apps_test_utils.h>
#include <dynslam/apps/progress.h>

#include <algorithm>
#include <regex>
#include <sstream>

using apps_test::configFile;
using apps_test::runCommand;

namespace
{
std::string q(const std::string& s) { return "'" + s + "'"; }

void expectOnePrefix(const apps_test::TCommandResult& r, const std::string& program)
{
	EXPECT_EQ(r.output.find("non-MRPT"), std::string::npos) << r.output;
	EXPECT_EQ(r.output.find("====="), std::string::npos) << r.output;
	EXPECT_EQ(r.output.find(program + ": " + program), std::string::npos) << r.output;
	EXPECT_EQ(r.output.find(program + ": error: " + program), std::string::npos) << r.output;
	EXPECT_NE(r.output.find(program + ": error: "), std::string::npos) << r.output;
}
}  // namespace

TEST(Messages, NoBannerAndNoDoubledProgramName)
{
	// A std exception (missing INI) in each app.
	const auto r = runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c /nonexistent.ini");
	EXPECT_EQ(r.exitCode, 1);
	expectOnePrefix(r, "dynslam-run");
	const auto c = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -c /nonexistent.ini");
	EXPECT_EQ(c.exitCode, 1);
	expectOnePrefix(c, "dynslam-compare");
	// Bad command lines (the app classes' own "bad command line" messages).
	const auto m = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " --no-such-option");
	EXPECT_EQ(m.exitCode, 1);
	expectOnePrefix(m, "dynslam-montecarlo");
	EXPECT_NE(m.output.find("dynslam-montecarlo: error: bad command line"), std::string::npos)
	    << m.output;
#ifdef DYNSLAM_SIMULATE_EXE
	const auto s = runCommand(std::string(q(DYNSLAM_SIMULATE_EXE)) + " --no-such-option");
	EXPECT_EQ(s.exitCode, 1);
	expectOnePrefix(s, "dynslam-simulate");
	EXPECT_NE(s.output.find("dynslam-simulate: error: bad command line"), std::string::npos)
	    << s.output;
#endif
}

TEST(Messages, OutputFolderThatCannotBeCreatedGetsASentence)
{
	const std::string dir = apps_test::freshDir("o");
	apps_test::writeFile(dir + "/afile", "x");
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " + q(configFile("run_highway.ini")) +
	               " --no-figures -o " + q(dir + "/afile/sub"));
	EXPECT_EQ(r.exitCode, 1) << r.output;
	EXPECT_NE(r.output.find("dynslam-run: error: cannot create the output folder '" + dir +
	                        "/afile/sub': '" + dir + "/afile' is a file, not a folder"),
	          std::string::npos)
	    << r.output;
	EXPECT_EQ(r.output.find("filesystem error"), std::string::npos) << r.output;
	const auto c = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -q --no-figures --out " +
	                          q(dir + "/afile"));
	EXPECT_EQ(c.exitCode, 1) << c.output;
	EXPECT_NE(c.output.find("is a file, not a folder"), std::string::npos) << c.output;
#ifdef DYNSLAM_SIMULATE_EXE
	const auto s = runCommand(std::string(q(DYNSLAM_SIMULATE_EXE)) + " -c " +
	                          q(configFile("highway.ini")) + " -o " + q(dir + "/afile/sub"));
	EXPECT_EQ(s.exitCode, 1) << s.output;
	EXPECT_NE(s.output.find("dynslam-simulate: error: cannot create the output folder"),
	          std::string::npos)
	    << s.output;
	EXPECT_EQ(s.output.find("filesystem error"), std::string::npos) << s.output;
#endif
}

#ifdef DYNSLAM_BACKEND_TABLE_EXE
TEST(Messages, BackendTableHelpExitsZero)
{
	const auto r = runCommand(std::string(q(DYNSLAM_BACKEND_TABLE_EXE)) + " --help");
	EXPECT_EQ(r.exitCode, 0) << r.output;
	EXPECT_NE(r.output.find("--scenario"), std::string::npos) << r.output;
	EXPECT_EQ(r.output.find("not found"), std::string::npos) << r.output;
	const auto bad = runCommand(std::string(q(DYNSLAM_BACKEND_TABLE_EXE)) + " --no-such-option");
	EXPECT_EQ(bad.exitCode, 1) << bad.output;
}
#endif

TEST(Messages, ProgressInARedirectedLogHasNoCarriageReturn)
{
	const auto r = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) +
	                          " --runs 10 --levels w1v1 --threads 2 --no-figures");
	ASSERT_EQ(r.exitCode, 0) << r.output;
	EXPECT_EQ(r.output.find('\r'), std::string::npos);
	EXPECT_EQ(r.output.find("[###"), std::string::npos) << r.output;
	// One plain line per tenth instead.
	for (int k = 1; k <= 10; ++k)
		EXPECT_NE(r.output.find(std::to_string(k) + "/10 runs (" + std::to_string(10 * k) + "%)"),
		          std::string::npos)
		    << k << "\n"
		    << r.output;
}

TEST(Messages, ProgressBarStyles)
{
	std::ostringstream os;
	{
		dynslam::apps::CProgressBar bar("runs", 20, os);  // not a terminal: Lines
		EXPECT_EQ(bar.style(), dynslam::apps::CProgressBar::Style::Lines);
		for (int i = 0; i < 20; ++i) bar.advance();
	}
	const std::string lines = os.str();
	EXPECT_EQ(lines.find('\r'), std::string::npos);
	EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 10) << lines;
	std::ostringstream bar;
	{
		dynslam::apps::CProgressBar b("runs", 3, bar, true,
		                              dynslam::apps::CProgressBar::Style::Bar);
		b.advance(3);
	}
	EXPECT_NE(bar.str().find('\r'), std::string::npos);
}

TEST(Messages, CompareLogsAProgressLinePerFilter)
{
	// progress_every = 30 stands for a long run (default: ten lines per filter from 2000 steps).
	const std::string dir = apps_test::freshDir("p");
	std::string ini = apps_test::shippedIniText("compare_highway.ini");
	ini = std::regex_replace(ini, std::regex("\\[Compare\\]"), "[Compare]\nprogress_every = 30");
	apps_test::writeFile(dir + "/c.ini", ini);
	const auto r = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -c " + q(dir + "/c.ini") +
	                          " -r " + q(apps_test::dataset("highway.rawlog")) + " --no-figures");
	ASSERT_EQ(r.exitCode, 0) << r.output;
	for (const char* f : {"static_all", "static_landmarks_only", "dynamic"})
	{
		EXPECT_NE(r.output.find(std::string(f) + " on 121 steps"), std::string::npos) << f;
		EXPECT_NE(r.output.find(std::string(f) + ": step 60/121"), std::string::npos) << f;
		EXPECT_NE(r.output.find(std::string(f) + ": step 121/121"), std::string::npos) << f;
	}
}
