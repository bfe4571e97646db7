/** dynslam-montecarlo without libmrpt-slam (doc/results/performance.md section 14): the executable
 * does not link it, and the back-ends that need it (MRPT's static filter, JCBB, the classify
 * association) come from the module libdynslam_slam_services.so, loaded on first use, with the
 * same results as the classes linked in (the in-process CMonteCarloApp of this test binary):
 * every written file byte for byte (runs.csv without its timing column). */
#include <apps_test_utils.h>
#include <dynslam/apps/CMonteCarloApp.h>

#include <regex>

using apps_test::TArgs;

namespace
{
std::string q(const std::string& s) { return "'" + s + "'"; }

/** runs.csv without its last column (ms_per_step: a wall time). */
std::vector<std::string> runsWithoutTiming(const std::string& path)
{
	std::vector<std::string> out;
	for (const auto& l : apps_test::readLines(path)) out.push_back(l.substr(0, l.rfind(',')));
	return out;
}

/** montecarlo.ini with the scenario's absolute path, `backend` and extra [DynamicKFSLAM] keys,
 * plus MRPT's static filter's section. */
std::string writeIni(const std::string& dir, const std::string& backend, const std::string& keys)
{
	std::string text = apps_test::shippedIniText("montecarlo.ini");
	text = std::regex_replace(text, std::regex("(^|\\n)scenario *= *"),
	                          "$1scenario = " + std::string(DYNSLAM_CONFIG_DIR) + "/");
	text =
	    std::regex_replace(text, std::regex("(^|\\n)backend *=[^\\n]*"), "$1backend = " + backend);
	text = std::regex_replace(text, std::regex("(^|\\n)\\[DynamicKFSLAM\\]\\n"),
	                          "$1[DynamicKFSLAM]\n" + keys + "\n");
	text += "\n[RangeBearingKFSLAM]\nstd_sensor_range = 0.01\nstd_sensor_yaw_deg = 0.0573\n";
	const std::string ini = dir + "/mc.ini";
	apps_test::writeFile(ini, text);
	return ini;
}
}  // namespace

TEST(MonteCarloSlamModule, ExecutableDoesNotNeedLibmrptSlam)
{
	const auto r = apps_test::runCommand("readelf -d " + q(DYNSLAM_MONTECARLO_EXE));
	if (r.exitCode != 0) GTEST_SKIP() << "readelf not available: " << r.output;
	EXPECT_NE(r.output.find("libmrpt-obs"), std::string::npos) << r.output;  // readelf worked
	EXPECT_EQ(r.output.find("libmrpt-slam"), std::string::npos) << r.output;
	EXPECT_EQ(r.output.find("libmrpt-vision"), std::string::npos) << r.output;
}

TEST(MonteCarloSlamModule, ModuleBackEndsEqualTheLinkedClasses)
{
	const std::string dir = apps_test::freshDir("module");
	struct TCase
	{
		const char* name;
		const char* backend;
		const char* keys;
	};
	for (const TCase& c : {TCase{"static_all", "static_all", ""},
	                       TCase{"jcbb", "ekf", "outlier_method = jcbb\ninnovation_gate = 0.999"},
	                       TCase{"classify", "ekf", "feature_labels = classify"}})
	{
		const std::string sub = dir + "/" + c.name;
		std::filesystem::create_directories(sub);
		const std::string ini = writeIni(sub, c.backend, c.keys);
		const std::string args = " --runs 2 --levels w1v1 --threads 2 --no-figures -q -c " + q(ini);
		const auto r = apps_test::runCommand(std::string(q(DYNSLAM_MONTECARLO_EXE)) + args +
		                                     " -o " + q(sub + "/exe"));
		ASSERT_EQ(r.exitCode, 0) << c.name << ": " << r.output;
		dynslam::apps::CMonteCarloApp app;
		TArgs a({"--runs", "2", "--levels", "w1v1", "--threads", "2", "--no-figures", "-q", "-c",
		         ini, "-o", sub + "/linked"});
		ASSERT_TRUE(app.initialize(a.argc(), a.argv())) << c.name;
		app.run();
		size_t files = 0;
		for (const auto& e : std::filesystem::directory_iterator(sub + "/linked"))
		{
			const std::string f = e.path().filename().string(), other = sub + "/exe/" + f;
			ASSERT_TRUE(std::filesystem::exists(other)) << c.name << ": " << f;
			if (f == "runs.csv")
				EXPECT_EQ(runsWithoutTiming(e.path().string()), runsWithoutTiming(other)) << c.name;
			else
				EXPECT_EQ(apps_test::readFile(e.path().string()), apps_test::readFile(other))
				    << c.name << ": " << f;
			++files;
		}
		EXPECT_GE(files, 6u) << c.name;
		// The static filter's joint landmark covariance reached the scoring (the "map" NEES).
		EXPECT_NE(apps_test::readFile(sub + "/exe/nees_summary.csv").find("w1v1,map,2,1,"),
		          std::string::npos)
		    << c.name;
	}
}
