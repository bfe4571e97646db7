/** Outputs that other tools read (issue 16, items 6-9, 11), the app classes driven directly
 * on the shipped highway dataset:
 *  - one time base: trajectory.tum of a --no-gt run is associated stamp by stamp with the
 *    shipped datasets/highway_gt_ego.tum, as evo_ape tum GT EST does (evo itself is not
 *    installable here: this is the same association, checked in C++);
 *  - --full-covariance: the written ego covariances equal getEgoPose().cov of the back-end
 *    replayed independently, bit for bit;
 *  - --scene: the file loads back with COpenGLScene::loadFromFile and holds the paths;
 *  - --video: cv::VideoCapture opens it and reads one frame per step;
 *  - dynslam-compare without ground truth: RMS differences to the dynamic row. */
#include <apps_test_utils.h>
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/CRunApp.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfLines.h>

#include <cmath>
#include <map>
#include <opencv2/videoio.hpp>
#include <sstream>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::TArgs;

namespace
{
/** TUM lines: t -> (x, y); every non-comment line must have 8 numbers (evo's reader). */
std::map<double, Eigen::Vector2d> readTum(const std::string& path)
{
	std::map<double, Eigen::Vector2d> out;
	for (const auto& l : apps_test::readLines(path))
	{
		if (l.empty() || l[0] == '#') continue;
		std::istringstream is(l);
		double v[8];
		for (double& x : v) EXPECT_TRUE(bool(is >> x)) << path << ": " << l;
		std::string extra;
		EXPECT_FALSE(bool(is >> extra)) << path << ": " << l;
		out[v[0]] = Eigen::Vector2d(v[1], v[2]);
	}
	return out;
}

/** The "ego" lines of a covariance file: step -> (t, 3x3). */
std::map<int, std::pair<std::string, Eigen::Matrix3d>> readEgoCov(const std::string& path)
{
	std::map<int, std::pair<std::string, Eigen::Matrix3d>> out;
	for (const auto& l : apps_test::readLines(path))
	{
		std::istringstream is(l);
		std::string kind, t;
		int step = 0;
		if (!(is >> kind) || kind != "ego") continue;
		is >> step >> t;
		Eigen::Matrix3d c;
		for (int i = 0; i < 9; ++i) is >> c(i / 3, i % 3);
		EXPECT_FALSE(is.fail()) << l;
		out[step] = {t, c};
	}
	return out;
}

CRunApp runApp(const std::vector<std::string>& extra, const std::string& out)
{
	CRunApp app;
	std::vector<std::string> a{
	    "-c", apps_test::configFile("run_highway.ini"), "-o", out, "-q", "--no-figures"};
	a.insert(a.end(), extra.begin(), extra.end());
	TArgs args(a);
	EXPECT_TRUE(app.initialize(args.argc(), args.argv()));
	app.run();
	return app;
}
}  // namespace

TEST(TimeBase, NoGtTrajectoryAssociatesWithTheShippedGroundTruth)
{
	const CRunApp withGt = runApp({}, apps_test::freshDir("gt"));
	const CRunApp noGt = runApp({"--no-gt"}, apps_test::freshDir("nogt"));
	ASSERT_TRUE(withGt.evaluation.has_value());
	const auto gt = readTum(apps_test::dataset("highway_gt_ego.tum"));
	const auto est = readTum(noGt.outDir + "/trajectory.tum");
	const auto estGt = readTum(withGt.outDir + "/trajectory.tum");
	ASSERT_EQ(gt.size(), 121u);
	ASSERT_EQ(est.size(), 121u);
	// One time base: with or without ground truth the same stamps, the rawlog's (1.6e9 s on).
	ASSERT_EQ(estGt.size(), est.size());
	for (auto a = est.begin(), b = estGt.begin(); a != est.end(); ++a, ++b)
		EXPECT_EQ(a->first, b->first);
	EXPECT_NEAR(est.begin()->first, 1.6e9, 1e-6);
	// evo's association: nearest stamp within max_diff (0.01 s); here they must coincide.
	double sum = 0;
	size_t matched = 0;
	for (const auto& [t, p] : est)
	{
		const auto it = gt.lower_bound(t - 1e-6);
		ASSERT_TRUE(it != gt.end() && std::abs(it->first - t) < 1e-6) << "no GT stamp for " << t;
		sum += (p - it->second).squaredNorm();
		++matched;
	}
	EXPECT_EQ(matched, 121u);
	// The associated pairs are the right ones: their RMS position error is the run's ATE
	// (no alignment), computed by the app from the ground-truth CSV by step index.
	const double ate = std::sqrt(sum / double(matched));
	std::cout << "ATE from the associated TUM files " << ate << " m, the app's "
	          << withGt.evaluation->metrics.ate << " m\n";
	EXPECT_NEAR(ate, withGt.evaluation->metrics.ate, 1e-6);
	// ego.csv's t column is the ground truth's t column.
	const auto egoCsv = apps_test::readLines(withGt.outDir + "/ego.csv");
	const auto gtCsv = apps_test::readLines(apps_test::dataset("highway_gt_ego.csv"));
	ASSERT_EQ(egoCsv.size(), gtCsv.size());
	for (size_t i = 1; i < egoCsv.size(); ++i)
		EXPECT_NEAR(std::stod(apps_test::splitCsv(egoCsv[i])[1]),
		            std::stod(apps_test::splitCsv(gtCsv[i])[1]), 1e-6)
		    << "line " << i;
}

TEST(FullCovariance, RunWritesTheBackendsEgoCovarianceAndTheMapBlocks)
{
	const std::string out = apps_test::freshDir("cov");
	const CRunApp app = runApp({"--full-covariance"}, out);
	const auto cov = readEgoCov(out + "/covariance.txt");
	ASSERT_EQ(cov.size(), 121u);
	// Independent replay of the same back-end with the app's effective INI.
	auto backend = makeBackend(app.backend, app.params);
	const TRawlog log = loadRawlog(app.rawlogFile);
	ASSERT_EQ(log.size(), 121u);
	for (size_t k = 0; k < log.size(); ++k)
	{
		backend->processActionObservation(log.actions[k], log.frames[k]);
		const Eigen::Matrix3d P = backend->getEgoPose().cov.asEigen();
		ASSERT_TRUE(cov.count(int(k)));
		EXPECT_EQ(cov.at(int(k)).second, P) << "step " << k;  // 17 digits: bit for bit
	}
	EXPECT_NEAR(std::stod(cov.at(0).first), 1.6e9, 1e-6);
	// Landmark, joint and object blocks at the end, one line each.
	size_t lm = 0, joint = 0, feat = 0, poses = 0;
	for (const auto& l : apps_test::readLines(out + "/covariance.txt"))
	{
		lm += l.rfind("landmark ", 0) == 0;
		joint += l.rfind("landmarks_joint_row ", 0) == 0;
		feat += l.rfind("object_feature ", 0) == 0;
		poses += l.rfind("object_pose ", 0) == 0;
	}
	EXPECT_EQ(lm, app.result.est.landmarks.size());
	EXPECT_EQ(joint, 2 * app.result.est.landmarks.size());
	EXPECT_EQ(feat, app.result.est.object_features.size());
	EXPECT_EQ(poses, app.result.est.object_poses.size());
	EXPECT_GT(poses, 0u);
}

TEST(FullCovariance, CompareWritesOneFilePerFilter)
{
	const std::string out = apps_test::freshDir("cmpcov");
	CCompareApp app;
	TArgs a({"--out", out, "-q", "--no-figures", "--filters", "static_landmarks_only,dynamic",
	         "--full-covariance"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	for (const auto& r : app.runs)
	{
		const auto cov = readEgoCov(out + "/" + r.name + "_covariance.txt");
		ASSERT_EQ(cov.size(), r.est.ego.size()) << r.name;
		for (const auto& e : r.est.ego) EXPECT_EQ(cov.at(e.step).second, e.cov) << r.name;
	}
}

namespace
{
double gtMinX(const CRunApp& app)
{
	double m = 1e300;
	for (const auto& e : app.gt.ego) m = std::min(m, e.x());
	return m;
}
double gtMaxX(const CRunApp& app)
{
	double m = -1e300;
	for (const auto& e : app.gt.ego) m = std::max(m, e.x());
	return m;
}
}  // namespace

TEST(SceneAndVideo, RunWritesASceneThatLoadsBackAndAVideoWithOneFramePerStep)
{
	const std::string out = apps_test::freshDir("scene");
	const CRunApp app =
	    runApp({"--scene", out + "/run.3Dscene", "--video", out + "/run.mp4"}, out + "/o");
	mrpt::opengl::COpenGLScene scene;
	ASSERT_TRUE(scene.loadFromFile(out + "/run.3Dscene"));
	auto ego = std::dynamic_pointer_cast<mrpt::opengl::CSetOfLines>(
	    scene.getByName(app.result.name + "/ego_path"));
	ASSERT_TRUE(ego) << "no " << app.result.name << "/ego_path";
	EXPECT_EQ(ego->getLineCount(), 120u);
	auto truth = std::dynamic_pointer_cast<mrpt::opengl::CSetOfLines>(
	    scene.getByName("ground_truth/ego_path"));
	ASSERT_TRUE(truth);
	EXPECT_EQ(truth->getLineCount(), 120u);
	EXPECT_FALSE(truth->getColor_u8() == ego->getColor_u8());
	auto lms = std::dynamic_pointer_cast<mrpt::opengl::CPointCloud>(
	    scene.getByName(app.result.name + "/landmarks"));
	ASSERT_TRUE(lms);
	EXPECT_EQ(lms->size(), app.result.est.landmarks.size());
	EXPECT_TRUE(scene.getByName(app.result.name + "/object_0_track"));
	// Framed on the data (issue 30 item 6: it opened at the origin) with a legend.
	const auto& cam = scene.getViewport()->getCamera();
	EXPECT_NEAR(cam.getPointingAtX(), 0.5 * (gtMinX(app) + gtMaxX(app)), 1.0);
	EXPECT_GT(cam.getZoomDistance(), 0.9 * (gtMaxX(app) - gtMinX(app)));
	EXPECT_TRUE(scene.getByName("legend/ground truth"));
	EXPECT_TRUE(scene.getByName("legend/" + app.result.name));

	cv::VideoCapture cap(out + "/run.mp4");
	ASSERT_TRUE(cap.isOpened());
	EXPECT_EQ(int(cap.get(cv::CAP_PROP_FRAME_WIDTH)), 960);
	int frames = 0;
	for (cv::Mat f; cap.read(f);) ++frames;
	EXPECT_EQ(frames, 121);
}

TEST(SceneAndVideo, CompareDrawsEveryFilter)
{
	const std::string out = apps_test::freshDir("cmpscene");
	CCompareApp app;
	TArgs a({"-q", "--no-figures", "--filters", "static_landmarks_only,dynamic", "--scene",
	         out + "/c.3Dscene", "--video", out + "/c.mp4"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	mrpt::opengl::COpenGLScene scene;
	ASSERT_TRUE(scene.loadFromFile(out + "/c.3Dscene"));
	for (const char* f : {"static_landmarks_only", "dynamic", "ground_truth"})
		EXPECT_TRUE(scene.getByName(std::string(f) + "/ego_path")) << f;
	cv::VideoCapture cap(out + "/c.mp4");
	ASSERT_TRUE(cap.isOpened());
	int frames = 0;
	for (cv::Mat f; cap.read(f);) ++frames;
	EXPECT_EQ(frames, 121);
}

TEST(CompareWithoutGroundTruth, DifferenceTableToTheDynamicRow)
{
	const std::string out = apps_test::freshDir("diff");
	CCompareApp app;
	TArgs a({"--no-gt", "--out", out, "-q", "--no-figures", "--filters",
	         "static_landmarks_only,dynamic"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_FALSE(app.hasGroundTruth);
	EXPECT_EQ(app.referenceFilter, "dynamic");
	ASSERT_EQ(app.rows.size(), 2u);
	const auto& self = app.rows[1].metrics;
	EXPECT_EQ(self.ego.x, 0.0);
	EXPECT_EQ(self.ego.y, 0.0);
	EXPECT_EQ(self.static_map.x, 0.0);
	// The other row: RMS of the per-step differences, recomputed here.
	const auto& a0 = app.runs[0].est.ego;
	const auto& a1 = app.runs[1].est.ego;
	ASSERT_EQ(a0.size(), a1.size());
	double sx = 0, sy = 0;
	for (size_t k = 0; k < a0.size(); ++k)
	{
		sx += std::pow(a0[k].mean.x() - a1[k].mean.x(), 2);
		sy += std::pow(a0[k].mean.y() - a1[k].mean.y(), 2);
	}
	const auto& m = app.rows[0].metrics;
	EXPECT_NEAR(m.ego.x, std::sqrt(sx / double(a0.size())), 1e-12);
	EXPECT_NEAR(m.ego.y, std::sqrt(sy / double(a0.size())), 1e-12);
	EXPECT_GT(m.ego.y, 0.0);
	EXPECT_TRUE(std::isfinite(m.static_map.y));
	EXPECT_GT(m.static_map.n_xy, 70u);  // the landmarks both filters have (80 in the truth)
	std::cout << app.tableText;
	EXPECT_NE(app.tableText.find("RMS DIFFERENCES to the 'dynamic' row"), std::string::npos);
	EXPECT_TRUE(std::filesystem::is_regular_file(out + "/differences.csv"));
	EXPECT_FALSE(std::filesystem::exists(out + "/metrics.csv"));
	// The map figure's title claims no ground truth.
	EXPECT_EQ(CCompareApp::mapTitle(false).find("over the ground truth"), std::string::npos);
	EXPECT_NE(CCompareApp::mapTitle(true).find("over the ground truth"), std::string::npos);
}
