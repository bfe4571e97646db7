/** Where the sensor noise comes from without a scenario file (issue 30 item 2,
 * dynslam/apps/noise_sources.h): the INI if it gives it, [RangeBearingKFSLAM]'s stds for the
 * dynamic filter, the rawlog observations' own sensor_std_range / sensor_std_yaw, else a clear
 * error. End to end on MRPT's simulator output (Debian package mrpt-apps). */
#include <apps_test_utils.h>
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/noise_sources.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/common/config_utils.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <filesystem>

using namespace dynslam::apps;

namespace
{
const char* kSimulLandmarks = "/usr/bin/simul-landmarks";

/** MRPT's simul_landmarks_demo INI made 2-D and short (as tests/apps/test_mrpt_inputs.cpp):
 * stdRange 0.01 m, stdYaw 0.1 deg; simul-landmarks writes them into every observation. */
std::string makeSimulLandmarksRawlog(const std::string& dir)
{
	apps_test::writeFile(
	    dir + "/sl.ini",
	    "[Params]\nrandom_seed = 123\nnSteps = 120\ncircularPath = 0\nsquarePathLength = 50\n"
	    "odometryNoiseXY_std = 0.04\nminSensorDistance = 0\nmaxSensorDistance = 6\n"
	    "fieldOfView_deg = 180\nstdRange = 0.01\nstdYaw_deg = 0.1\nstdPitch_deg = 0\n"
	    "outFile = sl.rawlog\noutDir = OUT\nshow_in_3d = false\n\n[RANDOMSET_1]\n"
	    "nLandmarks = 70\nmin_x = -4\nmax_x = 12\nmin_y = -3\nmax_y = 12\nmin_z = 0\nmax_z = 0\n");
	const auto r = apps_test::runCommand(std::string(kSimulLandmarks) + " sl.ini", dir);
	EXPECT_EQ(r.exitCode, 0) << r.output;
	return dir + "/OUT/sl.rawlog";
}

/** A rawlog of `n` steps whose observations carry the given stds (0: none). */
TRawlog syntheticRawlog(double stdRange, double stdYaw, size_t n = 3)
{
	TRawlog r;
	for (size_t k = 0; k < n; ++k)
	{
		auto sf = mrpt::obs::CSensoryFrame::Create();
		auto o = mrpt::obs::CObservationBearingRange::Create();
		o->sensor_std_range = float(stdRange);
		o->sensor_std_yaw = float(stdYaw);
		sf->insert(o);
		r.frames.push_back(sf);
		r.actions.push_back(mrpt::obs::CActionCollection::Create());
	}
	return r;
}

std::string errorOf(const std::function<void()>& f)
{
	try
	{
		f();
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}

bool contains(const std::string& s, const std::string& w) { return s.find(w) != std::string::npos; }
}  // namespace

TEST(NoiseSources, TheIniWinsWhenItGivesTheNoise)
{
	mrpt::config::CConfigFileMemory ini(
	    "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-5 1e-5]\n"
	    "[RangeBearingKFSLAM]\nstd_sensor_range = 0.5\nstd_sensor_yaw_deg = 2\n");
	const std::string before = ini.getContent();
	EXPECT_EQ(applyNoiseSources(ini, syntheticRawlog(0.01, 0.002), "DynamicKFSLAM",
	                            "RangeBearingKFSLAM", false),
	          "");
	EXPECT_EQ(ini.getContent(), before);
	// The same INI as the shipped default (no -c): its values do not count, the data's do.
	const std::string what = applyNoiseSources(ini, syntheticRawlog(0.01, 0.002), "DynamicKFSLAM",
	                                           "RangeBearingKFSLAM", true);
	EXPECT_TRUE(contains(what, "rawlog's observations")) << what;
	EXPECT_NEAR(ini.read_double("RangeBearingKFSLAM", "std_sensor_range", 0), 0.01, 1e-8);
	EXPECT_NEAR(ini.read_double("RangeBearingKFSLAM", "std_sensor_yaw_deg", 0),
	            double(float(0.002)) * 180 / M_PI, 1e-9);
	EXPECT_EQ(ini.read_string("DynamicKFSLAM", "measurement_model", ""), "range_bearing");
}

TEST(NoiseSources, DynamicFallsBackToMrptsSectionThenToTheObservations)
{
	// MRPT's kf-slam INI: no [DynamicKFSLAM] at all.
	mrpt::config::CConfigFileMemory mrpt(
	    "[RangeBearingKFSLAM]\nstd_sensor_range = 0.1\nstd_sensor_yaw_deg = 0.5\n");
	const std::string w = applyNoiseSources(mrpt, syntheticRawlog(0.01, 0.002), "DynamicKFSLAM",
	                                        "RangeBearingKFSLAM", false);
	EXPECT_TRUE(contains(w, "from [RangeBearingKFSLAM]")) << w;
	EXPECT_EQ(mrpt.read_string("DynamicKFSLAM", "measurement_model", ""), "range_bearing");
	const double sy = 0.5 * M_PI / 180;
	EXPECT_EQ(
	    mrpt.read_string("DynamicKFSLAM", "Sigma_v", ""),
	    dynslam::config::formatMatrix(Eigen::Vector2d(0.01, sy * sy).asDiagonal().toDenseMatrix()));
	// No section at all: the observations' stds, for both filters.
	mrpt::config::CConfigFileMemory empty;
	const std::string o = applyNoiseSources(empty, syntheticRawlog(0.02, 0.004), "DynamicKFSLAM",
	                                        "RangeBearingKFSLAM", false);
	EXPECT_TRUE(contains(o, "sensor_std_range = 0.02")) << o;
	const double r2 = double(float(0.02)) * double(float(0.02));
	const double y2 = double(float(0.004)) * double(float(0.004));
	EXPECT_EQ(empty.read_string("DynamicKFSLAM", "Sigma_v", ""),
	          dynslam::config::formatMatrix(Eigen::Vector2d(r2, y2).asDiagonal().toDenseMatrix()));
	EXPECT_NEAR(empty.read_double("RangeBearingKFSLAM", "std_sensor_range", 0), 0.02, 1e-8);
}

TEST(NoiseSources, ClearErrorsWhenNothingGivesTheNoise)
{
	mrpt::config::CConfigFileMemory empty;
	const std::string e = errorOf(
	    [&] { applyNoiseSources(empty, syntheticRawlog(0, 0), "DynamicKFSLAM", "", false); });
	EXPECT_TRUE(contains(e, "[DynamicKFSLAM] Sigma_v: required key is missing")) << e;
	EXPECT_TRUE(contains(e, "sensor_std_range")) << e;
	const std::string s = errorOf(
	    [&] { applyNoiseSources(empty, syntheticRawlog(0, 0), "", "RangeBearingKFSLAM", false); });
	EXPECT_TRUE(contains(s, "[RangeBearingKFSLAM] std_sensor_range")) << s;
	// A Cartesian model cannot take range-bearing stds.
	mrpt::config::CConfigFileMemory cart("[DynamicKFSLAM]\nmeasurement_model = cartesian\n");
	const std::string c = errorOf(
	    [&] { applyNoiseSources(cart, syntheticRawlog(0.01, 0.01), "DynamicKFSLAM", "", false); });
	EXPECT_TRUE(contains(c, "measurement_model = cartesian")) << c;
	// NaN or negative stds in the data are no noise.
	EXPECT_FALSE(observationNoise(syntheticRawlog(-0.1, 0.01)).has_value());
	EXPECT_FALSE(observationNoise(syntheticRawlog(std::nan(""), 0.01)).has_value());
	bool varying = true;
	TRawlog two = syntheticRawlog(0.01, 0.01, 1);
	const TRawlog other = syntheticRawlog(0.02, 0.01, 1);
	two.frames.push_back(other.frames[0]);
	ASSERT_TRUE(observationNoise(two, &varying).has_value());
	EXPECT_TRUE(varying);
	EXPECT_NEAR(observationNoise(two)->std_range, 0.01, 1e-8);
}

/** The turnkey run of issue 30 item 2: `dynslam-compare -r sl.rawlog` (no -c) on MRPT's
 * simulator output took the highway's noise (std_range 0.0032 m instead of 0.01). */
TEST(NoiseSources, CompareWithoutIniTakesTheNoiseOfMrptsSimulator)
{
	if (!std::filesystem::exists(kSimulLandmarks))
		GTEST_SKIP() << kSimulLandmarks << " not installed (Debian package mrpt-apps)";
	const std::string dir = apps_test::freshDir("sl");
	const std::string rawlog = makeSimulLandmarksRawlog(dir);
	CCompareApp app;
	apps_test::TArgs a({"-r", rawlog, "--filters", "static_all,dynamic,default", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	EXPECT_TRUE(contains(app.noiseUsed, "sensor_std_range = 0.01 m")) << app.noiseUsed;
	EXPECT_NEAR(app.params.read_double("RangeBearingKFSLAM", "std_sensor_range", 0), 0.01, 1e-8);
	EXPECT_NEAR(app.params.read_double("RangeBearingKFSLAM", "std_sensor_yaw_deg", 0), 0.1, 1e-6);
	ASSERT_EQ(app.rows.size(), 3u);
	for (const auto& row : app.rows)
	{
		ASSERT_TRUE(row.consistency.has_value()) << row.filter;
		const auto& nis = row.consistency->nis;
		std::printf("[  info    ] %s: ATE %.4f m, NIS inside %.3f, ANIS %.3f\n", row.filter.c_str(),
		            row.metrics.ate, nis.fraction_inside, nis.anees);
		EXPECT_LT(row.metrics.ate, 0.02) << row.filter;  // measured 0.0046-0.0047 m
		if (row.filter != "static_all")                  // MRPT's filter has no NIS record
		{
			EXPECT_GT(nis.fraction_inside, 0.8) << row.filter;
		}
	}
}

TEST(NoiseSources, MrptsKfSlamIniRunsTheDynamicRow)
{
	if (!std::filesystem::exists(kSimulLandmarks))
		GTEST_SKIP() << kSimulLandmarks << " not installed (Debian package mrpt-apps)";
	const std::string dir = apps_test::freshDir("kf");
	const std::string rawlog = makeSimulLandmarksRawlog(dir);
	// MRPT's own kf-slam INI as shipped (no [DynamicKFSLAM]): the dynamic row took to fail with
	// "[DynamicKFSLAM] measurement_model: required key is missing".
	CCompareApp app;
	apps_test::TArgs a({"-c", apps_test::configFile("kf-slam_highway.ini"), "-r", rawlog,
	                    "--filters", "static_all,dynamic", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	EXPECT_TRUE(contains(app.noiseUsed, "from [RangeBearingKFSLAM]")) << app.noiseUsed;
	EXPECT_EQ(app.params.read_string("DynamicKFSLAM", "measurement_model", ""), "range_bearing");
	ASSERT_EQ(app.rows.size(), 2u);
}

/** config/simul_landmarks.ini, the documented one-line run on simul-landmarks' output: no
 * noise keys, MRPT's start; on static data the dynamic row is MRPT's filter. */
TEST(NoiseSources, ShippedSimulLandmarksIni)
{
	if (!std::filesystem::exists(kSimulLandmarks))
		GTEST_SKIP() << kSimulLandmarks << " not installed (Debian package mrpt-apps)";
	const std::string dir = apps_test::freshDir("ini");
	const std::string rawlog = makeSimulLandmarksRawlog(dir);
	CCompareApp app;
	apps_test::TArgs a({"-c", apps_test::configFile("simul_landmarks.ini"), "-r", rawlog, "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	EXPECT_TRUE(contains(app.noiseUsed, "rawlog's observations")) << app.noiseUsed;
	ASSERT_TRUE(app.hasGroundTruth);
	ASSERT_EQ(app.rows.size(), 3u);
	EXPECT_EQ(app.rows[0].filter, "static_all");
	EXPECT_EQ(app.rows[1].filter, "dynamic");
	EXPECT_NEAR(app.rows[1].metrics.ate, app.rows[0].metrics.ate, 1e-9);
	EXPECT_LT(app.rows[1].metrics.ate, 0.02);  // measured 0.0047 m
	EXPECT_LT(app.rows[2].metrics.ate, 0.02);
}
