/** MRPT-native inputs (issue 16, items 1, 4, 5): a rawlog written by MRPT's simul-landmarks
 * (sensory frame, then action, per step) paired as kf-slam pairs it, with its ground-truth
 * files; bad MRPT ground-truth files; unknown keys in MRPT-owned INI sections. Format #2:
 * test_observations_only.cpp. simul-landmarks comes with the Debian package mrpt-apps
 * (scripts/install_deps.sh installs it). */
#include <apps_test_utils.h>
#include <dynslam/apps/CRunApp.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/mrpt_sections.h>
#include <dynslam/apps/rawlog_io.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::dataset;

namespace
{
const char* kSimulLandmarks = "/usr/bin/simul-landmarks";

/** MRPT's sample simul_landmarks_demo_EKF-SLAM.ini (MRPT 2.5.8, share/mrpt/config_files/
 * simul-landmarks), made 2-D (min_z = max_z = 0 and stdPitch_deg = 0: MRPT's 2-D filter, like
 * ours, rejects a non-zero pitch), shorter (nSteps), and with the 3-D window off. */
std::string simulLandmarksIni(int nSteps)
{
	return "[Params]\nrandom_seed = 123\nnSteps = " + std::to_string(nSteps) +
	       "\ncircularPath = 0\nsquarePathLength = 50\nodometryNoiseXY_std = 0.04\n"
	       "minSensorDistance = 0\nmaxSensorDistance = 6\nfieldOfView_deg = 180\n"
	       "stdRange = 0.01\nstdYaw_deg = 0.1\nstdPitch_deg = 0\n"
	       "outFile = sl.rawlog\noutDir = OUT\nshow_in_3d = false\n\n"
	       "[RANDOMSET_1]\nnLandmarks = 70\nmin_x = -4\nmax_x = 12\nmin_y = -3\nmax_y = 12\n"
	       "min_z = 0\nmax_z = 0\n";
}

/** Runs simul-landmarks in a fresh folder; returns the rawlog path. */
std::string makeSimulLandmarksRawlog(const std::string& tag, int nSteps)
{
	const std::string dir = apps_test::freshDir(tag);
	apps_test::writeFile(dir + "/sl.ini", simulLandmarksIni(nSteps));
	const auto r = apps_test::runCommand(std::string(kSimulLandmarks) + " sl.ini", dir);
	EXPECT_EQ(r.exitCode, 0) << r.output;
	return dir + "/OUT/sl.rawlog";
}

bool contains(const std::string& s, const std::string& what)
{
	return s.find(what) != std::string::npos;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Item 1 + 4: simul-landmarks output and its ground truth
// ---------------------------------------------------------------------------------------
TEST(SimulLandmarks, PairedAsKfSlamPairsWithNotes)
{
	if (!std::filesystem::exists(kSimulLandmarks))
		GTEST_SKIP() << kSimulLandmarks << " not installed (Debian package mrpt-apps)";
	const std::string rawlog = makeSimulLandmarksRawlog("sl", 60);
	const TRawlog r = loadRawlog(rawlog);
	// SF_0 ACT_0 ... SF_59 ACT_59: pairs (ACT_k, SF_k+1), SF_0 and ACT_59 dropped.
	EXPECT_EQ(r.entries, 120u);
	EXPECT_EQ(r.framesInFile, 60u);
	ASSERT_EQ(r.size(), 59u);
	for (size_t k = 0; k < r.size(); ++k) EXPECT_EQ(r.frameIndex[k], k + 1);
	// MRPT's normal order: notes, not warnings (issue 30: two warnings on every such file).
	EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
	ASSERT_EQ(r.notes.size(), 2u);
	EXPECT_TRUE(contains(r.notes[0], "sensory frame at entry 0 comes before any action"))
	    << r.notes[0];
	EXPECT_TRUE(contains(r.notes[1], "action at entry 119 has no sensory frame after it"))
	    << r.notes[1];
	EXPECT_TRUE(contains(r.notes[1], rawlog)) << r.notes[1];

	// The pairing is the physical one: the readings of pair k match the ground-truth pose of
	// row k + 1 (the pose after ACT_k), not row k. Range residuals vs stdRange = 0.01 m.
	const std::string gtSpec = groundTruthBesideRawlog(rawlog);
	ASSERT_TRUE(isMrptGroundTruthSpec(gtSpec)) << gtSpec;
	const io::TGroundTruth gt = loadGroundTruthForRawlog(gtSpec, r);
	ASSERT_EQ(gt.numSteps(), r.size());
	EXPECT_EQ(gt.landmarks.size(), 70u);
	double worstRight = 0, worstShifted = 0;
	size_t readings = 0;
	for (size_t k = 1; k < r.size(); ++k)
	{
		const auto obs = r.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		ASSERT_TRUE(obs);
		for (const auto& m : obs->sensedData)
		{
			const Eigen::Vector2d lm = gt.landmarks.at(m.landmarkID);
			worstRight =
			    std::max(worstRight, std::abs((lm - gt.ego[k].head<2>()).norm() - m.range));
			worstShifted =
			    std::max(worstShifted, std::abs((lm - gt.ego[k - 1].head<2>()).norm() - m.range));
			++readings;
		}
	}
	std::printf(
	    "[  info    ] %zu readings: worst range residual %.4f m (pairing), %.4f m "
	    "(shifted by one step)\n",
	    readings, worstRight, worstShifted);
	EXPECT_GT(readings, 200u);
	EXPECT_LT(worstRight, 0.05);    // 5 sigma
	EXPECT_GT(worstShifted, 0.15);  // the robot moves 0.2 m per step
}

TEST(SimulLandmarks, EveryBackendRunsOnItAgainstMrptGroundTruth)
{
	if (!std::filesystem::exists(kSimulLandmarks))
		GTEST_SKIP() << kSimulLandmarks << " not installed (Debian package mrpt-apps)";
	const std::string rawlog = makeSimulLandmarksRawlog("slrun", 120);
	const std::string dir = std::filesystem::path(rawlog).parent_path().parent_path().string();
	// Range-bearing model with simul-landmarks' noise (stdRange 0.01 m, stdYaw 0.1 deg). The EKF
	// starts like MRPT's filter (Sigma_0 = 0, no prediction on an empty map); the framework's
	// running cost needs a positive-definite prior.
	auto writeIni = [&](const std::string& name, const std::string& sigma0, bool skip)
	{
		apps_test::writeFile(
		    dir + "/" + name,
		    "[Run]\nrawlog = OUT/sl.rawlog\nground_truth = auto\nfigures = false\n"
		    "[DynamicKFSLAM]\nmeasurement_model = range_bearing\n"
		    "Sigma_v = [1e-4 3.0461741978670857e-06]\nmotion_noise = action\n"
		    "Sigma_0 = " +
		        sigma0 + "\nskip_prediction_on_empty_map = " + (skip ? "true" : "false") +
		        "\n[RangeBearingKFSLAM]\nstd_sensor_range = 0.01\nstd_sensor_yaw_deg = 0.1\n"
		        "[Backend]\nbackend = vdo\n");
		return dir + "/" + name;
	};
	const std::string mrptLike = writeIni("run.ini", "[0 0 0]", true);
	const std::string prior = writeIni("run_prior.ini", "[1e-8 1e-8 1e-10]", false);
	std::map<std::string, double> ate;
	for (const std::string backend : {"ekf", "static_all", "vdo"})
	{
		CRunApp app;
		apps_test::TArgs a({"-c", backend == "vdo" ? prior : mrptLike, "-o",
		                    dir + "/out_" + backend, "--backend", backend, "-q"});
		ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
		app.logging_enable_keep_record = true;
		app.run();
		// MRPT's normal order: no warning (issue 30; the notes are logged at DEBUG level).
		std::istringstream log(app.getLogAsString());
		for (std::string line; std::getline(log, line);)
		{
			if (contains(line, "has no sensory frame after it") ||
			    contains(line, "comes before any action"))
			{
				EXPECT_TRUE(contains(line, "|DEBUG|")) << line;
			}
		}
		ASSERT_TRUE(app.hasGroundTruth) << backend;
		EXPECT_TRUE(isMrptGroundTruthSpec(app.groundTruthUsed)) << app.groundTruthUsed;
		ASSERT_TRUE(app.evaluation.has_value());
		const auto& m = app.evaluation->metrics;
		std::printf(
		    "[  info    ] %s on simul-landmarks (119 steps): ego ATE %.4f m, theta RMSE %.5f "
		    "rad, map RMSE x %.4f y %.4f m\n",
		    backend.c_str(), m.ate, m.ego.theta, m.static_map.x, m.static_map.y);
		EXPECT_EQ(app.result.steps, 119u);
		EXPECT_LT(m.ate, 0.02) << backend;  // measured 0.0047 (ekf, static_all), 0.0037 (vdo)
		EXPECT_LT(m.ego.theta, 0.004) << backend;  // measured 0.00084 (ekf, static_all)
		ate[backend] = m.ate;
	}
	// With MRPT's start the dynamic EKF is MRPT's filter on static data (README).
	EXPECT_NEAR(ate["ekf"], ate["static_all"], 1e-9);
}

TEST(MrptGroundTruth, BadFilesNameFileAndLine)
{
	const std::string dir = apps_test::freshDir("mgt");
	const std::string path = dir + "/x.rawlog_ground_truth_robot_path.txt";
	const std::string lms = dir + "/x.rawlog_ground_truth.txt";
	EXPECT_EQ(mrptLandmarksFileFor(path), lms);
	EXPECT_EQ(mrptLandmarksFileFor(dir + "/h_gt_robot_path.txt"), dir + "/h_gt_landmarks.txt");
	EXPECT_THROW(mrptLandmarksFileFor(dir + "/h_gt_ego.csv"), std::runtime_error);
	auto err = [&](const std::string& p, const std::string& l, size_t rows)
	{
		apps_test::writeFile(path, p);
		apps_test::writeFile(lms, l);
		try
		{
			io::readMrptGroundTruth(path, lms, rows, {0, 1}, {0.0, 1.0});
		}
		catch (const std::runtime_error& e)
		{
			return std::string(e.what());
		}
		return std::string();
	};
	const std::string goodPath = "% x y z yaw pitch roll\n0 0 0 0 0 0\n1 0 0 0.1 -0 0\n";
	const std::string goodLm = "1 2 0 5 0 0 1\n3 4 0 5 0 0 2\n";
	EXPECT_EQ(err(goodPath, goodLm, 2), "");
	std::string e = err("0 0 0 0 0 0\n1 0 0 0.1\n", goodLm, 2);
	EXPECT_TRUE(contains(e, path + ":2: 4 columns, expected 6")) << e;
	e = err("0 0 0 0 0 0\n1 0 0.5 0.1 0 0\n", goodLm, 2);
	EXPECT_TRUE(contains(e, ":2: not a 2-D pose")) << e;
	e = err(goodPath, goodLm, 3);
	EXPECT_TRUE(contains(e, "2 poses, expected 3")) << e;
	e = err(goodPath, "1 2 -4 5 0 0 1\n", 2);
	EXPECT_TRUE(contains(e, lms + ":1: landmark z = -4")) << e;
	e = err(goodPath, "1 2 0 5 0 0 1\n1 2 0 5 0 0 1\n", 2);
	EXPECT_TRUE(contains(e, "duplicate landmark ID 1")) << e;
	e = err(goodPath, "1 2 0 5 0 0 abc\n", 2);
	EXPECT_TRUE(contains(e, "'abc' is not a finite number")) << e;
	std::filesystem::remove(lms);
	try
	{
		io::readMrptGroundTruth(path, lms, 2, {0, 1}, {0.0, 1.0});
		FAIL();
	}
	catch (const std::runtime_error& x)
	{
		EXPECT_TRUE(contains(x.what(), lms)) << x.what();
	}
}

// ---------------------------------------------------------------------------------------
// Item 5: MRPT-owned INI sections
// ---------------------------------------------------------------------------------------
TEST(MrptSections, UnknownKeysWarnOrFailWithTheFileName)
{
	mrpt::config::CConfigFileMemory ini(
	    "[RangeBearingKFSLAM]\nstd_sensor_range = 0.1\nstd_sensor_rang = 0.2\n"
	    "STD_SENSOR_YAW_DEG = 1\n"
	    "[RangeBearingKFSLAM_KalmanFilter]\nmethod = kfEKFNaive\nmethd = 1\n"
	    "[DynamicKFSLAM_KalmanFilter]\nverbosity_level = LVL_WARN\nenable_profilr = true\n");
	const auto u = unknownMrptKeys(ini);
	ASSERT_EQ(u.size(), 3u);
	EXPECT_EQ(u[0],
	          "[RangeBearingKFSLAM] std_sensor_rang: unknown key (misspelled?), ignored by MRPT");
	EXPECT_TRUE(contains(u[1], "[RangeBearingKFSLAM_KalmanFilter] methd")) << u[1];
	EXPECT_TRUE(contains(u[2], "[DynamicKFSLAM_KalmanFilter] enable_profilr")) << u[2];
	const auto w = checkMrptSections(ini, "my.ini", false);
	ASSERT_EQ(w.size(), 3u);
	EXPECT_TRUE(contains(w[0], "config file 'my.ini': [RangeBearingKFSLAM] std_sensor_rang"));
	try
	{
		checkMrptSections(ini, "my.ini", true);
		FAIL() << "strict must throw";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_TRUE(contains(e.what(), "config file 'my.ini'")) << e.what();
		EXPECT_TRUE(contains(e.what(), "std_sensor_rang")) << e.what();
	}
	// The shipped INIs are clean.
	for (const char* f :
	     {"run_highway.ini", "compare_highway.ini", "compare_tunnel.ini", "compare_classified.ini",
	      "compare_turning_braking.ini", "compare_kitti.ini", "mrclam_compare.ini",
	      "montecarlo.ini", "simul_landmarks.ini", "kf-slam_highway.ini",
	      "compare_kitti_detections.ini", "compare_tunnel_markov.ini", "run_longrun.ini"})
	{
		mrpt::config::CConfigFileMemory c;
		loadIniFile(apps_test::configFile(f), c);
		EXPECT_TRUE(unknownMrptKeys(c).empty()) << f << ": " << unknownMrptKeys(c).front();
		EXPECT_TRUE(unknownSections(c).empty()) << f << ": " << unknownSections(c).front();
	}
}

// Issue 30 item 9: misspelled section names were silently ignored.
TEST(MrptSections, UnknownSectionsWarnWithTheNearestNameOrFailWithStrict)
{
	mrpt::config::CConfigFileMemory ini(
	    "[OdometryNoice]\na = 1\n[DynamicKFSLAM_KalmanFiltr]\nmethod = kfEKFNaive\n"
	    "[dynamickfslam]\nSigma_v = [1 1]\n[Totally]\nx = 1\n"
	    // the model's module sections are known; a misspelled one is named
	    "[ObjectModel]\ncv_dt = 0.5\n[OdometryBias]\nodometry_dt = 0.1\n[Classify]\n"
	    "classify_alpha = 0.1\n[Clasify]\nclassify_beta = 0.1\n");
	auto u = unknownSections(ini);  // in MRPT's section order (sorted); sorted here too
	std::sort(u.begin(), u.end());
	ASSERT_EQ(u.size(), 4u);
	EXPECT_EQ(u[0], "section [Clasify] is read by no app (did you mean [Classify]?), ignored");
	EXPECT_EQ(u[1],
	          "section [DynamicKFSLAM_KalmanFiltr] is read by no app (did you mean "
	          "[DynamicKFSLAM_KalmanFilter]?), ignored");
	EXPECT_EQ(u[2],
	          "section [OdometryNoice] is read by no app (did you mean [OdometryNoise]?), "
	          "ignored");
	EXPECT_EQ(u[3], "section [Totally] is read by no app, ignored");  // no near name
	const auto w = checkMrptSections(ini, "my.ini", false);
	ASSERT_EQ(w.size(), 4u);
	EXPECT_TRUE(contains(w[0], "config file 'my.ini': section [")) << w[0];
	EXPECT_THROW(checkMrptSections(ini, "my.ini", true), std::invalid_argument);
}
