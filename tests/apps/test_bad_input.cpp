/** Bad input to the executables: a clear message and exit code 1, never a crash. Each case
 * runs the real executable (paths from CMake) with its output captured. */
#include <apps_test_utils.h>
#include <dynslam/io/ground_truth.h>

#include <random>
#include <regex>

using apps_test::configFile;
using apps_test::dataset;
using apps_test::runCommand;

namespace
{
std::string q(const std::string& s) { return "'" + s + "'"; }

/** Expects a normal exit with code 1 and every `needles` string in the output. */
void expectCleanFailure(const apps_test::TCommandResult& r, const std::vector<std::string>& needles)
{
	ASSERT_TRUE(r.exitedNormally) << "crashed:\n" << r.output;
	EXPECT_EQ(r.exitCode, 1) << r.output;
	for (const auto& n : needles)
		EXPECT_NE(r.output.find(n), std::string::npos) << "'" << n << "' not in:\n" << r.output;
}

/** A copy of a shipped INI with one line replaced (the key at the start of the line) and
 * relative paths made absolute. */
std::string editedIni(const std::string& dir, const std::string& shipped, const std::string& key,
                      const std::string& newLine)
{
	std::string text = apps_test::shippedIniText(shipped);
	text =
	    std::regex_replace(text, std::regex("\\.\\./datasets"), std::string(DYNSLAM_DATASETS_DIR));
	text = std::regex_replace(text, std::regex("(^|\\n)" + key + " *=[^\\n]*"), "$1" + newLine);
	const std::string p = dir + "/" + shipped;
	apps_test::writeFile(p, text);
	return p;
}
}  // namespace

TEST(BadInput, MissingRawlog)
{
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " + q(configFile("run_highway.ini")) +
	               " -r /nonexistent/none.rawlog -o " + q(apps_test::freshDir("o")));
	expectCleanFailure(r,
	                   {"dynslam-run: error", "rawlog '/nonexistent/none.rawlog': file not found"});
	const auto c = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -r /nonexistent/none.rawlog");
	expectCleanFailure(c, {"dynslam-compare: error", "/nonexistent/none.rawlog': file not found"});
}

TEST(BadInput, CorruptRawlog)
{
	const std::string dir = apps_test::freshDir("c");
	std::mt19937 rng(7);
	std::string bytes(4096, '\0');
	for (char& ch : bytes) ch = char(rng() & 0xFF);
	apps_test::writeFile(dir + "/garbage.rawlog", bytes);
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " + q(configFile("run_highway.ini")) +
	               " -r " + q(dir + "/garbage.rawlog") + " -o " + q(dir + "/out"));
	expectCleanFailure(r, {"garbage.rawlog': corrupt or truncated at entry 0"});
	// A truncated copy of the real rawlog.
	apps_test::writeFile(dir + "/cut.rawlog",
	                     apps_test::readFile(dataset("highway.rawlog")).substr(0, 9000));
	const auto c =
	    runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -q -r " + q(dir + "/cut.rawlog"));
	expectCleanFailure(c, {"cut.rawlog': corrupt or truncated at entry"});
}

TEST(BadInput, GroundTruthOfAnotherLength)
{
	// The shipped ground truth cut to 100 steps.
	const std::string dir = apps_test::freshDir("gt");
	dynslam::io::TGroundTruth gt = dynslam::io::readGroundTruth(DYNSLAM_DATASETS_DIR, "highway");
	gt.t.resize(100);
	gt.ego.resize(100);
	for (auto& o : gt.objects)
	{
		o.features.resize(100);
		o.pose.resize(100);
		o.visible.resize(100);
	}
	dynslam::io::writeGroundTruth(gt, dir, "short");
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " + q(configFile("run_highway.ini")) +
	               " --gt " + q(dir + "/short") + " -o " + q(dir + "/out"));
	expectCleanFailure(r, {"does not match rawlog", "100 steps", "121 action/observation pairs"});
	const auto c =
	    runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -q --gt " + q(dir + "/short"));
	expectCleanFailure(c, {"does not match rawlog"});
}

TEST(BadInput, IniWithBadValues)
{
	const std::string dir = apps_test::freshDir("ini");
	// dynamic EKF option
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " +
	               q(editedIni(dir, "run_highway.ini", "Sigma_v", "Sigma_v = [1e-5 abc]")) +
	               " -o " + q(dir + "/out"));
	expectCleanFailure(r, {"[DynamicKFSLAM] Sigma_v", "abc"});
	// misspelled [Run] key
	const auto k = runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " +
	                          q(editedIni(dir, "run_highway.ini", "figures", "figurez = true")) +
	                          " -o " + q(dir + "/out"));
	expectCleanFailure(k, {"figurez", "unknown"});
	// MRPT filter's R (compare)
	const auto c = runCommand(
	    std::string(q(DYNSLAM_COMPARE_EXE)) + " -c " +
	    q(editedIni(dir, "compare_highway.ini", "std_sensor_range", "std_sensor_range = -0.1")));
	expectCleanFailure(c, {"[RangeBearingKFSLAM] std_sensor_range"});
	// unknown filter name
	const auto f = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " --filters static_all,ukf");
	expectCleanFailure(f, {"unknown filter 'ukf'"});
	// Monte Carlo: a noise level that does not exist, a zero run count
	const auto m =
	    runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " --levels w1v1,w4v4 --runs 1 -q");
	expectCleanFailure(m, {"w4v4"});
	const auto z = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " --runs 0 -q");
	expectCleanFailure(z, {"[MonteCarlo] runs"});
	// missing config file, unknown option
	const auto n = runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c /nonexistent.ini");
	expectCleanFailure(n, {"config file '/nonexistent.ini' not found"});
	const auto u = runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " --bogus-flag");
	ASSERT_TRUE(u.exitedNormally) << u.output;
	EXPECT_EQ(u.exitCode, 1) << u.output;
}

TEST(BadInput, HelpExitsZero)
{
	for (const char* exe : {DYNSLAM_RUN_EXE, DYNSLAM_COMPARE_EXE, DYNSLAM_MONTECARLO_EXE})
	{
		const auto r = runCommand(q(exe) + " --help");
		EXPECT_EQ(r.exitCode, 0) << exe << "\n" << r.output;
		EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
	}
}

TEST(BadInput, IniErrorsNameTheFile)
{
	const std::string dir = apps_test::freshDir("inifile");
	const std::string ini = editedIni(dir, "run_highway.ini", "Sigma_v", "Sigma_v = [1e-5 abc]");
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " -c " + q(ini) + " -o " + q(dir + "/out"));
	expectCleanFailure(r, {"config file '" + ini + "': [DynamicKFSLAM] Sigma_v", "abc"});
	const std::string cini =
	    editedIni(dir, "compare_highway.ini", "std_sensor_range", "std_sensor_range = -0.1");
	const auto c = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -q -c " + q(cini));
	expectCleanFailure(c, {"config file '" + cini + "': [RangeBearingKFSLAM] std_sensor_range"});
}

TEST(BadInput, MontecarloIniErrorsNameTheFile)
{
	// [MonteCarlo] errors (a missing required key, a bad value) name the INI file.
	const std::string dir = apps_test::freshDir("mcinifile");
	const std::string shipped = apps_test::shippedIniText("montecarlo.ini");
	const std::string ini = dir + "/mc.ini";
	apps_test::writeFile(
	    ini, std::regex_replace(shipped, std::regex("(^|\\n)scenario *=[^\\n]*"), "$1"));
	const auto r = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " -q --runs 1 -c " + q(ini));
	expectCleanFailure(
	    r, {"config file '" + ini + "': [MonteCarlo] scenario: required key is missing"});
	std::string text = std::regex_replace(shipped, std::regex("(^|\\n)scenario *= *"),
	                                      "$1scenario = " + std::string(DYNSLAM_CONFIG_DIR) + "/");
	apps_test::writeFile(
	    ini, std::regex_replace(text, std::regex("(^|\\n)threads *=[^\\n]*"), "$1threads = -2"));
	const auto b = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " -q --runs 1 -c " + q(ini));
	expectCleanFailure(b, {"config file '" + ini + "': [MonteCarlo] threads = '-2'"});
}

TEST(BadInput, MisspelledKeyInMrptSectionWarnsOrFailsWithStrict)
{
	const std::string dir = apps_test::freshDir("mrptkey");
	// A misspelled key in MRPT's own section: MRPT would silently ignore it.
	const std::string ini = editedIni(dir, "compare_highway.ini", "std_sensor_range",
	                                  "std_sensor_range = 0.0031622776601683794\n"
	                                  "std_sensor_rnage = 0.5");
	const std::string out = dir + "/out";
	const auto w = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -q --no-figures -c " +
	                          q(ini) + " --filters static_landmarks_only");
	ASSERT_TRUE(w.exitedNormally) << w.output;
	EXPECT_EQ(w.exitCode, 0) << w.output;
	EXPECT_NE(w.output.find("config file '" + ini +
	                        "': [RangeBearingKFSLAM] std_sensor_rnage: unknown key"),
	          std::string::npos)
	    << w.output;
	const auto s = runCommand(std::string(q(DYNSLAM_COMPARE_EXE)) + " -q --strict -c " + q(ini) +
	                          " --filters static_landmarks_only");
	expectCleanFailure(s, {"std_sensor_rnage: unknown key", "--strict"});
	// The same through dynslam-run, in [DynamicKFSLAM_KalmanFilter] (MRPT's TKF_options).
	const std::string rini =
	    editedIni(dir, "run_highway.ini", "enable_profiler", "enable_profilr = false");
	const auto r =
	    runCommand(std::string(q(DYNSLAM_RUN_EXE)) + " --strict -c " + q(rini) + " -o " + q(out));
	expectCleanFailure(r, {"[DynamicKFSLAM_KalmanFilter] enable_profilr: unknown key"});
}

TEST(BadInput, MontecarloStrictRejectsAMisspelledMrptKey)
{
	const std::string dir = apps_test::freshDir("mcstrict");
	std::string text = apps_test::shippedIniText("montecarlo.ini");
	text = std::regex_replace(text, std::regex("\\[DynamicKFSLAM_KalmanFilter\\]"),
	                          "[DynamicKFSLAM_KalmanFilter]\nenable_profilr = false");
	text = std::regex_replace(text, std::regex("(^|\\n)scenario *= *"),
	                          "$1scenario = " + std::string(DYNSLAM_CONFIG_DIR) + "/");
	const std::string ini = dir + "/mc.ini";
	apps_test::writeFile(ini, text);
	const auto r = runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + " --strict -q --runs 1 " +
	                          "--levels w1v1 -c " + q(ini));
	expectCleanFailure(r, {"config file '" + ini + "'",
	                       "[DynamicKFSLAM_KalmanFilter] enable_profilr: unknown key"});
}
