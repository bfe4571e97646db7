/** Files: MRPT reads the rawlog, rawlog-edit and kf-slam (mrpt-apps) accept it, outputs are
 * bit-identical for identical seeds, and datasets/ regenerates identically. */
#include <dynslam/io/ground_truth.h>
#include <dynslam/sim/CSimulateApp.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <regex>

#include "sim_test_utils.h"

using namespace dynslam::sim;
namespace fs = std::filesystem;

namespace
{
std::string tmpDir(const std::string& name)
{
	const auto d = fs::path(DYNSLAM_BINARY_DIR) / "test_tmp" / name;
	fs::remove_all(d);
	fs::create_directories(d);
	return d.string();
}

/** Runs the app class with these arguments (argv[0] added). */
CSimulateApp runApp(std::vector<std::string> args)
{
	args.insert(args.begin(), "dynslam-simulate");
	std::vector<const char*> argv;
	for (const auto& a : args) argv.push_back(a.c_str());
	CSimulateApp app;
	app.setMinLoggingLevel(mrpt::system::LVL_WARN);
	if (app.initialize(int(argv.size()), argv.data())) app.run();
	return app;
}

std::string gunzip(const std::string& path)
{
	mrpt::io::CFileGZInputStream f(path);
	std::string out;
	std::array<char, 65536> buf;
	for (size_t n; (n = f.Read(buf.data(), buf.size())) > 0;) out.append(buf.data(), n);
	return out;
}

/** Runs a shell command; returns its exit status and stdout+stderr. */
int runCommand(const std::string& cmd, std::string& output)
{
	output.clear();
	FILE* p = popen((cmd + " 2>&1").c_str(), "r");
	if (!p) return -1;
	std::array<char, 4096> buf;
	for (size_t n; (n = fread(buf.data(), 1, buf.size(), p)) > 0;) output.append(buf.data(), n);
	const int st = pclose(p);
	return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

const char* kGtSuffixes[] = {"_gt_ego.csv",
                             "_gt_ego.tum",
                             "_gt_landmarks.csv",
                             "_gt_objects.csv",
                             "_gt_object_features.csv",
                             "_gt_landmarks.txt",
                             "_gt_robot_path.txt",
                             "_gt_data_association.txt",
                             "_scenario.ini"};

/** kf-slam DA performance totals: TP FP TN FN unknown. */
std::array<long, 5> daPerformance(const std::string& file)
{
	std::array<long, 5> s{0, 0, 0, 0, 0};
	std::ifstream f(file);
	std::string line;
	while (std::getline(f, line))
	{
		if (line.empty() || line[0] == '%') continue;
		std::istringstream is(line);
		double t, idx;
		long v[5];
		if (is >> t >> idx >> v[0] >> v[1] >> v[2] >> v[3] >> v[4])
			for (int i = 0; i < 5; ++i) s[i] += v[i];
	}
	return s;
}

/** Writes an INI for kf-slam with absolute paths for this scenario, output in the build dir. */
std::string kfSlamIni(const std::string& dir, const std::string& base, const std::string& outDir)
{
	mrpt::config::CConfigFileMemory c(
	    dynslam_test::readFile(std::string(DYNSLAM_CONFIG_DIR) + "/kf-slam_highway.ini"));
	const std::string S = "MappingApplication";
	c.write(S, "rawlog_file", dir + "/" + base + ".rawlog");
	c.write(S, "ground_truth_file", dir + "/" + base + "_gt_landmarks.txt");
	c.write(S, "ground_truth_file_robot", dir + "/" + base + "_gt_robot_path.txt");
	c.write(S, "ground_truth_data_association", dir + "/" + base + "_gt_data_association.txt");
	c.write(S, "logOutput_dir", outDir);
	const std::string ini = outDir + ".ini";
	std::ofstream(ini) << c.getContent();
	return ini;
}
}  // namespace

TEST(SimRawlog, MrptReadsTheRawlog)
{
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const dynslam::io::TGroundTruth gt = buildGroundTruth(o);
	const TSimulatedRun run = simulateMeasurements(gt, o, o.noise_seed);
	const std::string dir = tmpDir("rawlog_read");
	std::ostringstream ini;
	o.dumpToTextStream(ini);
	writeRawlog(run, dir + "/h.rawlog", ini.str());

	mrpt::obs::CRawlog r;
	ASSERT_TRUE(r.loadFromRawLogFile(dir + "/h.rawlog"));
	ASSERT_EQ(r.size(), 2 * gt.numSteps());  // 242 for the highway
	for (size_t i = 0; i < r.size(); ++i)
		EXPECT_EQ(r.getType(i), i % 2 == 0 ? mrpt::obs::CRawlog::etActionCollection
		                                   : mrpt::obs::CRawlog::etSensoryFrame)
		    << "entry " << i;
	EXPECT_EQ(r.getCommentText(), ini.str());
	// The comment is the effective configuration: it loads back.
	EXPECT_EQ(loadScenarioFromText(r.getCommentText()).Sigma_w, o.Sigma_w);

	// kf-slam's reading loop: readActionObservationPair gives N + 1 pairs.
	mrpt::io::CFileGZInputStream f(dir + "/h.rawlog");
	auto ar = mrpt::serialization::archiveFrom(f);
	mrpt::obs::CActionCollection::Ptr act;
	mrpt::obs::CSensoryFrame::Ptr sf;
	size_t entry = 0, pairs = 0;
	while (mrpt::obs::CRawlog::readActionObservationPair(ar, act, sf, entry)) ++pairs;
	EXPECT_EQ(pairs, gt.numSteps());

	// What a reader gets back from the file: the same increments, Sigma_w as their covariance
	// (not a covariance rebuilt from MRPT's default motion model), the same readings.
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		const auto a = r.getAsAction(2 * k)->getActionByClass<mrpt::obs::CActionRobotMovement2D>();
		const auto a0 = run.actions[k]->getActionByClass<mrpt::obs::CActionRobotMovement2D>();
		ASSERT_TRUE(a && a0);
		mrpt::poses::CPose2D mean, mean0;
		mrpt::math::CMatrixDouble33 cov, cov0;
		a->poseChange->getCovarianceAndMean(cov, mean);
		a0->poseChange->getCovarianceAndMean(cov0, mean0);
		EXPECT_EQ(mean, mean0) << "k " << k;
		EXPECT_EQ(cov.asEigen(), k == 0 ? Eigen::Matrix3d::Zero() : o.Sigma_w) << "k " << k;
		const auto ob = r.getAsObservations(2 * k + 1)
		                    ->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		const auto ob0 =
		    run.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		ASSERT_TRUE(ob && ob0);
		ASSERT_EQ(ob->sensedData.size(), ob0->sensedData.size());
		for (size_t i = 0; i < ob->sensedData.size(); ++i)
		{
			EXPECT_EQ(ob->sensedData[i].range, ob0->sensedData[i].range);
			EXPECT_EQ(ob->sensedData[i].yaw, ob0->sensedData[i].yaw);
			EXPECT_EQ(ob->sensedData[i].landmarkID, ob0->sensedData[i].landmarkID);
		}
		EXPECT_EQ(ob->timestamp, ob0->timestamp);
		EXPECT_EQ(ob->maxSensorDistance, ob0->maxSensorDistance);
		EXPECT_EQ(ob->sensor_std_range, ob0->sensor_std_range);
	}

	// Streaming writes the same bytes.
	simulateToRawlog(gt, o, o.noise_seed, dir + "/s.rawlog", ini.str());
	EXPECT_EQ(gunzip(dir + "/s.rawlog"), gunzip(dir + "/h.rawlog"));
}

TEST(SimRawlog, SameSeedsGiveBitIdenticalFiles)
{
	const std::string a = tmpDir("bitident_a"), b = tmpDir("bitident_b"), c = tmpDir("bitident_c");
	const std::string cfg = dynslam_test::highwayIni();
	const CSimulateApp appA = runApp({"-c", cfg, "-o", a});
	runApp({"-c", cfg, "-o", b});
	runApp({"-c", cfg, "-o", c, "--noise-seed", "2"});
	EXPECT_EQ(appA.numRawlogEntries, 242u);
	for (const char* s : kGtSuffixes)
		EXPECT_EQ(dynslam_test::readFile(a + "/highway" + s),
		          dynslam_test::readFile(b + "/highway" + s))
		    << s;
	EXPECT_EQ(dynslam_test::readFile(a + "/highway.rawlog"),
	          dynslam_test::readFile(b + "/highway.rawlog"));
	EXPECT_NE(gunzip(a + "/highway.rawlog"), gunzip(c + "/highway.rawlog"));
	EXPECT_EQ(dynslam_test::readFile(a + "/highway_gt_ego.csv"),
	          dynslam_test::readFile(c + "/highway_gt_ego.csv"));
}

TEST(SimRawlog, TunnelDatasetRegeneratesIdentically)
{
	// The documented command: dynslam-simulate -c config/tunnel.ini -o datasets
	const std::string ds = DYNSLAM_DATASETS_DIR;
	ASSERT_TRUE(fs::exists(ds + "/tunnel.rawlog")) << "datasets/tunnel.rawlog missing";
	const std::string out = tmpDir("tunnel_regen");
	runApp({"-c", std::string(DYNSLAM_CONFIG_DIR) + "/tunnel.ini", "-o", out});
	for (const char* s : kGtSuffixes)
		EXPECT_EQ(dynslam_test::readFile(out + "/tunnel" + s),
		          dynslam_test::readFile(ds + "/tunnel" + s))
		    << "datasets/tunnel" << s << " differs from a fresh regeneration";
	EXPECT_EQ(gunzip(out + "/tunnel.rawlog"), gunzip(ds + "/tunnel.rawlog"));
	EXPECT_EQ(dynslam_test::readFile(out + "/tunnel_gt_classes.csv"),
	          dynslam_test::readFile(ds + "/tunnel_gt_classes.csv"));
}

TEST(SimRawlog, DatasetRegeneratesIdentically)
{
	const std::string ds = DYNSLAM_DATASETS_DIR;
	ASSERT_TRUE(fs::exists(ds + "/highway.rawlog")) << "datasets/highway.rawlog missing";
	const std::string out = tmpDir("dataset_regen");
	// The documented command: dynslam-simulate -c config/highway.ini -o datasets
	runApp({"-c", dynslam_test::highwayIni(), "-o", out});
	for (const char* s : kGtSuffixes)
		EXPECT_EQ(dynslam_test::readFile(out + "/highway" + s),
		          dynslam_test::readFile(ds + "/highway" + s))
		    << "datasets/highway" << s << " differs from a fresh regeneration";
	EXPECT_EQ(gunzip(out + "/highway.rawlog"), gunzip(ds + "/highway.rawlog"));
	EXPECT_EQ(dynslam_test::readFile(out + "/highway_gt_classes.csv"),
	          dynslam_test::readFile(ds + "/highway_gt_classes.csv"));
	// The shipped ground truth reads back.
	const dynslam::io::TGroundTruth gt = dynslam::io::readGroundTruth(ds, "highway");
	EXPECT_EQ(gt.numSteps(), 121u);
	EXPECT_EQ(gt.objects.size(), 3u);
}

TEST(SimRawlog, RawlogEditListsAllEntries)
{
	const std::string exe = "/usr/bin/rawlog-edit";
	if (!fs::exists(exe)) GTEST_SKIP() << exe << " not installed (Debian package mrpt-apps)";
	std::string out;
	const int rc = runCommand(
	    exe + " -i " + std::string(DYNSLAM_DATASETS_DIR) + "/highway.rawlog --info", out);
	ASSERT_EQ(rc, 0) << out;
	std::smatch m;
	ASSERT_TRUE(std::regex_search(out, m, std::regex("Overall number of objects\\s*:\\s*(\\d+)")))
	    << out;
	EXPECT_EQ(std::stoi(m[1]), 243);  // 121 ACT + 121 SF + the comment (scenario INI)
	EXPECT_TRUE(std::regex_search(out, std::regex("Actions/SensoryFrame format\\s*:\\s*Yes")))
	    << out;
	ASSERT_TRUE(std::regex_search(out, m, std::regex("RB\\s*/\\s*(\\d+)\\s*/"))) << out;
	EXPECT_EQ(std::stoi(m[1]), 121);
}

TEST(SimRawlog, KfSlamRunsOnTheHighwayAndIsAccurateWithoutMovers)
{
	const std::string exe = "/usr/bin/kf-slam";
	if (!fs::exists(exe)) GTEST_SKIP() << exe << " not installed (Debian package mrpt-apps)";
	// 1) The shipped highway rawlog, unchanged (moving features corrupt the static filter,
	//    but it must read everything and match every reading with the DA ground truth).
	const std::string ds = DYNSLAM_DATASETS_DIR;
	const std::string outH = tmpDir("kfslam") + "/highway";
	std::string log;
	ASSERT_EQ(runCommand(exe + " " + kfSlamIni(ds, "highway", outH), log), 0) << log;
	EXPECT_NE(log.find("KF-SLAM finished"), std::string::npos);
	const auto daH = daPerformance(outH + "/data_association_performance.log");
	EXPECT_GT(daH[0], 1000);  // true positives
	EXPECT_EQ(daH[4], 0);     // every reading had a DA ground-truth row (timestamps match)

	// 2) The same highway without the agents: the static filter is accurate.
	const std::string dir = tmpDir("kfslam_static");
	runApp({"-c", std::string(DYNSLAM_CONFIG_DIR) + "/highway_static_scenario.ini", "-o", dir});
	const std::string outS = dir + "/out";
	ASSERT_EQ(runCommand(exe + " " + kfSlamIni(dir, "highway_static", outS), log), 0) << log;
	std::smatch m;
	ASSERT_TRUE(std::regex_search(log, m, std::regex("Mean Error: ([0-9.eE+-]+) meters"))) << log;
	EXPECT_LT(std::stod(m[1]), 0.1);
	const auto daS = daPerformance(outS + "/data_association_performance.log");
	EXPECT_EQ(daS[1], 0);  // no false positives
	EXPECT_EQ(daS[3], 0);
	EXPECT_EQ(daS[4], 0);
	mrpt::math::CMatrixDouble pose;
	pose.loadFromTextFile(outS + "/robot_pose_00120.txt");
	const dynslam::io::TGroundTruth gt = dynslam::io::readGroundTruth(dir, "highway_static");
	EXPECT_LT(std::hypot(pose(0, 0) - gt.ego.back()[0], pose(1, 0) - gt.ego.back()[1]), 1.0);
	std::cout << "[          ] kf-slam highway: DA TP " << daH[0] << " TN " << daH[2]
	          << "; static-only: mean landmark error " << m[1] << " m, final pose error "
	          << std::hypot(pose(0, 0) - gt.ego.back()[0], pose(1, 0) - gt.ego.back()[1]) << " m\n";
}

TEST(SimRawlog, KfSlamGroundTruthFilesLoadAsMrptMatrices)
{
	// kf-slam loads these with CMatrix{Float,Double}::loadFromTextFile ('%' lines are comments).
	const std::string ds = DYNSLAM_DATASETS_DIR;
	const dynslam::io::TGroundTruth gt = dynslam::io::readGroundTruth(ds, "highway");
	mrpt::math::CMatrixDouble lm, path, da;
	lm.loadFromTextFile(ds + "/highway_gt_landmarks.txt");
	path.loadFromTextFile(ds + "/highway_gt_robot_path.txt");
	da.loadFromTextFile(ds + "/highway_gt_data_association.txt");
	ASSERT_EQ(lm.cols(), 7);  // x y z type seenCount tLastSeen ID
	ASSERT_EQ(size_t(lm.rows()), gt.landmarks.size());
	for (int r = 0; r < lm.rows(); ++r)
	{
		const auto& p = gt.landmarks.at(int32_t(lm(r, 6)));
		EXPECT_NEAR(lm(r, 0), p[0], 1e-9);
		EXPECT_NEAR(lm(r, 1), p[1], 1e-9);
	}
	ASSERT_EQ(path.cols(), 6);  // x y z yaw pitch roll
	ASSERT_EQ(size_t(path.rows()), gt.numSteps());
	for (size_t k = 0; k < gt.numSteps(); ++k)
	{
		EXPECT_NEAR(path(k, 0), gt.ego[k][0], 1e-9);
		EXPECT_NEAR(path(k, 3), gt.ego[k][2], 1e-12);
	}
	// One row per reading; timestamps equal Clock::toDouble of the rawlog's observations.
	const TScenarioOptions o = dynslam_test::highwayOptions();
	const TSimulatedRun run = simulateMeasurements(gt, o, o.noise_seed);
	ASSERT_EQ(da.cols(), 3);
	int row = 0;
	for (size_t k = 0; k < run.frames.size(); ++k)
	{
		const auto obs =
		    run.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		for (size_t i = 0; i < obs->sensedData.size(); ++i, ++row)
		{
			ASSERT_LT(row, da.rows());
			EXPECT_EQ(da(row, 0), mrpt::Clock::toDouble(obs->timestamp));
			EXPECT_EQ(da(row, 1), double(i));
			EXPECT_EQ(da(row, 2), double(obs->sensedData[i].landmarkID));
		}
	}
	EXPECT_EQ(row, da.rows());
}

TEST(SimRawlog, AppStreamModeWritesTheSameRawlog)
{
	const std::string cfg = std::string(DYNSLAM_CONFIG_DIR) + "/generated_small_scenario.ini";
	const std::string a = tmpDir("stream_a"), b = tmpDir("stream_b");
	const CSimulateApp inMemory = runApp({"-c", cfg, "-o", a});
	const CSimulateApp streamed = runApp({"-c", cfg, "-o", b, "--stream"});
	EXPECT_EQ(streamed.numRawlogEntries, 2 * 201u);
	EXPECT_GT(inMemory.numMeasurements, 0u);
	EXPECT_EQ(gunzip(a + "/generated_small.rawlog"), gunzip(b + "/generated_small.rawlog"));
	EXPECT_FALSE(fs::exists(b + "/generated_small_gt_data_association.txt"));
	mrpt::obs::CRawlog r;
	ASSERT_TRUE(r.loadFromRawLogFile(b + "/generated_small.rawlog"));
	EXPECT_EQ(r.size(), 2 * 201u);
}

TEST(SimRawlog, AppCommandLineAndFigure)
{
	const std::string dir = tmpDir("app_cli");
	EXPECT_THROW(runApp({"-o", dir}), std::invalid_argument);  // missing --config
	EXPECT_THROW(runApp({"-c", dynslam_test::highwayIni(), "--noise", "w9v9"}),
	             std::invalid_argument);
	EXPECT_THROW(runApp({"-c", dir + "/missing.ini"}), std::runtime_error);
	EXPECT_THROW(runApp({"-c", dynslam_test::highwayIni(), "--figure-only"}),
	             std::invalid_argument);
	const CSimulateApp help = runApp({"--help"});
	EXPECT_TRUE(help.writtenFiles.empty());
	const CSimulateApp app =
	    runApp({"-c", dynslam_test::highwayIni(), "-o", dir, "--name", "h3", "--noise", "w3v1",
	            "--world-seed", "0", "--noise-seed", "0", "--figure", dir + "/fig.png"});
	EXPECT_EQ(app.options.noise_level, "w3v1");
	EXPECT_EQ(app.options.Sigma_0, app.options.Sigma_w);
	mrpt::img::CImage img;
	ASSERT_TRUE(img.loadFromFile(dir + "/fig.png"));
	EXPECT_EQ(img.getWidth(), 1800);
	// The effective configuration records the overrides.
	const TScenarioOptions eff = loadScenario(dir + "/h3_scenario.ini");
	EXPECT_EQ(eff.noise_level, "w3v1");
	EXPECT_EQ(eff.world_seed, 0u);
	EXPECT_EQ(eff.noise_seed, 0u);
	EXPECT_EQ(eff.Sigma_v, app.options.Sigma_v);
	for (const auto& f : app.writtenFiles) EXPECT_TRUE(fs::exists(f)) << f;
}
