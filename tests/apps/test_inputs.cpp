/** Input handling of the apps: the rawlog loader (good, missing, corrupt, truncated, empty
 * files), ground-truth specs and the step-count check, scenario noise, shipped-file lookup. */
#include <apps_test_utils.h>
#include <dynslam/apps/data_files.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::dataset;

namespace
{
std::string loadError(const std::string& path)
{
	try
	{
		loadRawlog(path);
	}
	catch (const std::runtime_error& e)
	{
		return e.what();
	}
	return "";
}
bool contains(const std::string& s, const std::string& what)
{
	return s.find(what) != std::string::npos;
}
}  // namespace

TEST(RawlogIO, ShippedHighwayHasOnePairPerGroundTruthStep)
{
	const TRawlog r = loadRawlog(dataset("highway.rawlog"));
	const io::TGroundTruth gt = io::readGroundTruth(DYNSLAM_DATASETS_DIR, "highway");
	EXPECT_EQ(r.size(), gt.numSteps());
	EXPECT_EQ(r.size(), 121u);  // 60 s at 0.5 s, k = 0..120
	EXPECT_EQ(r.frames.size(), r.actions.size());
	// One comment object, then ACT_k, SF_k.
	EXPECT_EQ(r.entries, 2 * r.size() + 1);
}

TEST(RawlogIO, OdometryCovarianceSurvivesTheFile)
{
	// The simulator's Sigma_w (level w2v2) must come back from the file, not MRPT's default
	// motion model (which emOdometry actions get on reading).
	const TRawlog r = loadRawlog(dataset("highway.rawlog"));
	for (size_t k = 1; k < r.size(); k += 30)
	{
		const auto a = r.actions[k]->getActionByClass<mrpt::obs::CActionRobotMovement2D>();
		ASSERT_TRUE(a);
		const auto g =
		    std::dynamic_pointer_cast<mrpt::poses::CPosePDFGaussian>(a->poseChange.get_ptr());
		ASSERT_TRUE(g);
		EXPECT_NEAR(g->cov(0, 0), 1e-5, 1e-12) << "step " << k;
		EXPECT_NEAR(g->cov(1, 1), 1e-5, 1e-12) << "step " << k;
		EXPECT_NEAR(g->cov(2, 2), 1e-7, 1e-14) << "step " << k;
	}
}

TEST(RawlogIO, MissingFileNamesTheFile)
{
	const std::string p = "/nonexistent/dir/none.rawlog";
	const std::string e = loadError(p);
	EXPECT_TRUE(contains(e, p)) << e;
	EXPECT_TRUE(contains(e, "not found")) << e;
	const std::string d = apps_test::freshDir("dir");
	EXPECT_TRUE(contains(loadError(d), "is a directory")) << loadError(d);
}

TEST(RawlogIO, GarbageBytesAreRejected)
{
	const std::string p = apps_test::freshDir("g") + "/garbage.rawlog";
	std::mt19937 rng(42);
	std::string bytes(5000, '\0');
	for (char& c : bytes) c = char(rng() & 0xFF);
	apps_test::writeFile(p, bytes);
	const std::string e = loadError(p);
	EXPECT_TRUE(contains(e, p)) << e;
	EXPECT_TRUE(contains(e, "corrupt or truncated at entry 0")) << e;
	for (char c : e) EXPECT_TRUE(c >= 32 && c <= 126) << "non-printable byte in the message";
}

TEST(RawlogIO, TruncatedFileIsRejectedNotShortened)
{
	const std::string full = apps_test::readFile(dataset("highway.rawlog"));
	ASSERT_GT(full.size(), 12000u);
	const std::string p = apps_test::freshDir("t") + "/truncated.rawlog";
	apps_test::writeFile(p, full.substr(0, 10000));  // cuts the gz stream in an object
	const std::string e = loadError(p);
	EXPECT_TRUE(contains(e, p)) << e;
	EXPECT_TRUE(contains(e, "corrupt or truncated")) << e;
	EXPECT_TRUE(contains(e, "complete action/observation pairs")) << e;
}

TEST(RawlogIO, EmptyFileHasNoPairs)
{
	const std::string p = apps_test::freshDir("e") + "/empty.rawlog";
	apps_test::writeFile(p, "");
	const std::string e = loadError(p);
	EXPECT_TRUE(contains(e, "no action/observation pair")) << e;
	EXPECT_TRUE(contains(e, p)) << e;
}

TEST(GroundTruthFiles, SpecForms)
{
	auto s = parseGroundTruthSpec("a/b/highway");
	EXPECT_EQ(s.dir, "a/b");
	EXPECT_EQ(s.base, "highway");
	s = parseGroundTruthSpec("a/b/highway_gt_ego.csv");
	EXPECT_EQ(s.dir, "a/b");
	EXPECT_EQ(s.base, "highway");
	s = parseGroundTruthSpec("highway");
	EXPECT_EQ(s.dir, ".");
	EXPECT_THROW(parseGroundTruthSpec(""), std::runtime_error);
	EXPECT_EQ(groundTruthBesideRawlog(dataset("highway.rawlog")), dataset("highway"));
	EXPECT_EQ(groundTruthBesideRawlog("/nonexistent/x.rawlog"), "");
}

TEST(GroundTruthFiles, StepCountMustMatchTheRawlog)
{
	const io::TGroundTruth gt = loadGroundTruthFor(dataset("highway"), 121, "r.rawlog");
	EXPECT_EQ(gt.numSteps(), 121u);
	try
	{
		loadGroundTruthFor(dataset("highway"), 100, "my.rawlog");
		FAIL() << "expected a mismatch error";
	}
	catch (const std::runtime_error& e)
	{
		const std::string m = e.what();
		EXPECT_TRUE(contains(m, "does not match rawlog 'my.rawlog'")) << m;
		EXPECT_TRUE(contains(m, "121 steps")) << m;
		EXPECT_TRUE(contains(m, "100 action/observation pairs")) << m;
	}
	try
	{
		loadGroundTruthFor("/nonexistent/base", 121, "r.rawlog");
		FAIL() << "expected a missing-file error";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_TRUE(contains(e.what(), "/nonexistent/base_gt_ego.csv")) << e.what();
	}
}

TEST(ScenarioNoise, ReadAndApply)
{
	const TScenarioNoise n = readScenarioNoise(dataset("highway_scenario.ini"));
	EXPECT_EQ(n.level, "w2v2");
	EXPECT_NEAR(n.Sigma_v(0, 0), 1e-5, 1e-15);
	EXPECT_NEAR(n.Sigma_w(2, 2), 1e-7, 1e-17);
	EXPECT_NEAR(n.std_range, std::sqrt(1e-5), 1e-12);
	EXPECT_NEAR(n.std_yaw_deg, std::sqrt(1e-5) / 27.5 * 180 / M_PI, 1e-9);
	mrpt::config::CConfigFileMemory ini("[DynamicKFSLAM]\nmeasurement_model = cartesian\n");
	applyScenarioNoise(ini, n, "DynamicKFSLAM", "RangeBearingKFSLAM");
	EXPECT_EQ(ini.read_string("DynamicKFSLAM", "Sigma_v", ""), "[1e-05 0; 0 1e-05]");
	EXPECT_NEAR(ini.read_double("RangeBearingKFSLAM", "std_sensor_range", 0), n.std_range, 1e-15);
	EXPECT_THROW(readScenarioNoise("/nonexistent.ini"), std::runtime_error);
}

TEST(ShippedFiles, FoundFromAnywhereOrListed)
{
	// From the build tree the source tree is the last fallback (DYNSLAM_SOURCE_DIR).
	const std::string p = locateShippedFile("config/compare_highway.ini");
	EXPECT_TRUE(std::filesystem::is_regular_file(p)) << p;
	try
	{
		locateShippedFile("config/no_such_file.ini");
		FAIL();
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_TRUE(contains(e.what(), "tried:")) << e.what();
		EXPECT_GE(shippedFileCandidates("x").size(), 2u);
	}
}
