/** MRPT-native inputs, part 2 (issue 16, item 2): observations-only rawlogs (format #2:
 * CObservationOdometry + CObservationBearingRange) converted to the back-ends' pairs, bad input
 * to the reader (truncated files, odometry without timestamps, a NaN sensor pose), and what
 * MRPT 2.5.8 does to an emOdometry action's covariance when a rawlog is read. */
#include <apps_test_utils.h>
#include <dynslam/apps/app_common.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <limits>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::dataset;

namespace
{
bool contains(const std::string& s, const std::string& what)
{
	return s.find(what) != std::string::npos;
}

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

Eigen::Vector3d increment(const mrpt::obs::CActionCollection& a)
{
	const auto m = a.getBestMovementEstimation();
	const mrpt::poses::CPosePDFGaussian g(*m->poseChange);
	return {g.mean.x(), g.mean.y(), g.mean.phi()};
}
}  // namespace

// ---------------------------------------------------------------------------------------
// Item 2: observations-only rawlogs (format #2)
// ---------------------------------------------------------------------------------------
namespace
{
struct TFormat2Options
{
	bool odometryTimestamps = true;
	bool nanSensorPose = false;
	bool withOdometry = true;
};

/** The shipped highway as a format-#2 rawlog: a cumulative odometry reading (the composition of
 * the action means) 1 ms before each bearing-range observation, and a copy of the first
 * observation 100 ms before any odometry (to be dropped with a warning). */
std::string writeFormat2(const std::string& path, const TRawlog& src, const TFormat2Options& o)
{
	mrpt::io::CFileGZOutputStream f(path);
	auto ar = mrpt::serialization::archiveFrom(f);
	mrpt::poses::CPose2D odo;
	for (size_t k = 0; k < src.size(); ++k)
	{
		auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
		    *src.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>());
		if (o.nanSensorPose && k == 3)
			obs->sensorLocationOnRobot.x(std::numeric_limits<double>::quiet_NaN());
		const auto m = src.actions[k]->getBestMovementEstimation();
		odo = odo + mrpt::poses::CPosePDFGaussian(*m->poseChange).mean;
		if (k == 0)
		{
			// an observation before any odometry: dropped with a warning
			auto early = std::make_shared<mrpt::obs::CObservationBearingRange>(*obs);
			early->timestamp = obs->timestamp - std::chrono::milliseconds(100);
			ar << *early;
		}
		if (o.withOdometry)
		{
			mrpt::obs::CObservationOdometry od;
			od.odometry = odo;
			od.timestamp = o.odometryTimestamps ? obs->timestamp - std::chrono::milliseconds(1)
			                                    : INVALID_TIMESTAMP;
			ar << od;
		}
		ar << *obs;
	}
	return path;
}
}  // namespace

TEST(ObservationsOnly, ConvertedToPairsWithTheOdometryIncrements)
{
	const TRawlog h = loadRawlog(dataset("highway.rawlog"));
	const std::string p = writeFormat2(apps_test::freshDir("f2") + "/f2.rawlog", h, {});
	TOdometryNoiseOptions noise;
	noise.a1 = noise.a2 = noise.a3 = noise.a4 = 0;
	noise.minStdXY = 0.05;
	noise.minStdPHI = 2 * M_PI / 180;
	const TRawlog r = loadRawlog(p, noise);
	EXPECT_EQ(r.format, TRawlog::Format::ObservationsOnly);
	ASSERT_EQ(r.size(), h.size());
	EXPECT_EQ(r.framesInFile, h.size() + 1);
	ASSERT_EQ(r.warnings.size(), 1u);
	EXPECT_TRUE(contains(r.warnings[0], "1 bearing-range observation(s) before the first odometry"))
	    << r.warnings[0];
	double worst = 0;
	for (size_t k = 0; k < r.size(); ++k)
	{
		EXPECT_EQ(r.frameIndex[k], k + 1);
		const Eigen::Vector3d u = increment(*r.actions[k]), uh = increment(*h.actions[k]);
		worst = std::max(worst, (u - uh).cwiseAbs().maxCoeff());
		// the observation (and its timestamp) is the original one
		const auto o = r.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		const auto oh = h.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		EXPECT_EQ(o->timestamp, oh->timestamp);
		EXPECT_EQ(o->sensedData.size(), oh->sensedData.size());
		const mrpt::poses::CPosePDFGaussian g(
		    *r.actions[k]->getBestMovementEstimation()->poseChange);
		EXPECT_EQ(r.actions[k]->getBestMovementEstimation()->timestamp, o->timestamp);
		if (k == 0)
			EXPECT_EQ(g.cov.asEigen().norm(), 0.0);  // no motion before the first step
		else
		{
			// MRPT's Gaussian model with a1..a4 = 0: std minStdPHI on phi; on x, y minStdXY plus
			// the heading std carried over the increment (MRPT's formula: compared with MRPT's
			// own computeFromOdometry on the same increment and options).
			EXPECT_NEAR(g.cov(2, 2), std::pow(2 * M_PI / 180, 2), 1e-15) << k;
			EXPECT_GE(g.cov(0, 0), 0.05 * 0.05 * (1 - 1e-12)) << k;
			mrpt::obs::CActionRobotMovement2D::TMotionModelOptions mo;
			mo.gaussianModel = {0, 0, 0, 0, 0.05, 2 * M_PI / 180};
			mrpt::obs::CActionRobotMovement2D direct;
			direct.computeFromOdometry(mrpt::poses::CPose2D(u[0], u[1], u[2]), mo);
			const mrpt::poses::CPosePDFGaussian gdir(*direct.poseChange);
			EXPECT_LT((g.cov.asEigen() - gdir.cov.asEigen()).cwiseAbs().maxCoeff(), 1e-15) << k;
		}
	}
	std::printf("[  info    ] format #2 increments vs the format-#1 actions: max |diff| %.3g\n",
	            worst);
	EXPECT_LT(worst, 1e-9);  // composing then differencing the odometry poses
}

TEST(ObservationsOnly, EveryBackendGetsTheSameEstimates)
{
	// motion_noise = config: the odometry covariance is the INI's Sigma_w for both files, so
	// the only difference is the increments' round trip through cumulative odometry.
	const TRawlog h = loadRawlog(dataset("highway.rawlog"));
	const TRawlog r = loadRawlog(writeFormat2(apps_test::freshDir("f2b") + "/f2.rawlog", h, {}));
	mrpt::config::CConfigFileMemory ini;
	loadIniFile(apps_test::configFile("run_highway.ini"), ini);
	ini.write("DynamicKFSLAM", "motion_noise", "config");
	ini.write("DynamicKFSLAM", "Sigma_w", "[1e-5 1e-5 1e-7]");
	ini.write("Backend", "backend", "vdo");
	for (const std::string b : {"ekf", "vdo"})
	{
		auto f1 = makeBackend(b, ini);
		auto f2 = makeBackend(b, ini);
		const TFilterRun a = runFilter(*f1, h.actions, h.frames);
		const TFilterRun c = runFilter(*f2, r.actions, r.frames);
		ASSERT_EQ(a.est.ego.size(), c.est.ego.size());
		double d = 0;
		for (size_t k = 0; k < a.est.ego.size(); ++k)
			d = std::max(d, (a.est.ego[k].mean - c.est.ego[k].mean).cwiseAbs().maxCoeff());
		std::printf("[  info    ] %s: format #1 vs #2 ego max |diff| %.3g\n", b.c_str(), d);
		EXPECT_LT(d, 1e-6) << b;
	}
	// MRPT's static filter always takes the action's covariance, here MRPT's Gaussian model
	// instead of the file's Sigma_w: not the same numbers, but as accurate.
	const io::TGroundTruth gt = io::readGroundTruth(DYNSLAM_DATASETS_DIR, "highway");
	double ate[2];
	for (int i = 0; i < 2; ++i)
	{
		auto f = makeBackend("static_landmarks_only", ini);
		const TRawlog& src = i == 0 ? h : r;
		ate[i] = evaluateRun(gt, runFilter(*f, src.actions, src.frames).est).metrics.ate;
	}
	std::printf("[  info    ] static_landmarks_only ATE: format #1 %.4f m, format #2 %.4f m\n",
	            ate[0], ate[1]);
	EXPECT_LT(ate[1], 2 * ate[0] + 0.05);
}

TEST(ObservationsOnly, BadInputIsAClearError)
{
	const TRawlog h = loadRawlog(dataset("highway.rawlog"));
	const std::string dir = apps_test::freshDir("f2bad");
	// odometry without timestamps
	TFormat2Options o;
	o.odometryTimestamps = false;
	std::string e = loadError(writeFormat2(dir + "/nots.rawlog", h, o));
	EXPECT_TRUE(contains(e, dir + "/nots.rawlog")) << e;
	EXPECT_TRUE(contains(e, "CObservationOdometry without a timestamp")) << e;
	// no odometry at all
	o = {};
	o.withOdometry = false;
	e = loadError(writeFormat2(dir + "/noodo.rawlog", h, o));
	EXPECT_TRUE(contains(e, "but no CObservationOdometry")) << e;
	// a NaN sensor pose
	o = {};
	o.nanSensorPose = true;
	e = loadError(writeFormat2(dir + "/nan.rawlog", h, o));
	EXPECT_TRUE(contains(e, "sensorLocationOnRobot is not finite")) << e;
	EXPECT_TRUE(contains(e, "entry ")) << e;
	// truncated: the gz stream cut inside an object
	const std::string full = apps_test::readFile(writeFormat2(dir + "/full.rawlog", h, {}));
	ASSERT_GT(full.size(), 12000u);
	apps_test::writeFile(dir + "/cut.rawlog", full.substr(0, 10000));
	e = loadError(dir + "/cut.rawlog");
	EXPECT_TRUE(contains(e, dir + "/cut.rawlog")) << e;
	EXPECT_TRUE(contains(e, "corrupt or truncated at entry")) << e;
	// decreasing odometry timestamps
	{
		mrpt::io::CFileGZOutputStream f(dir + "/back.rawlog");
		auto ar = mrpt::serialization::archiveFrom(f);
		mrpt::obs::CObservationOdometry a, b;
		a.timestamp = mrpt::Clock::fromDouble(10);
		b.timestamp = mrpt::Clock::fromDouble(9);
		ar << a << b;
	}
	e = loadError(dir + "/back.rawlog");
	EXPECT_TRUE(contains(e, "entry 1: odometry timestamps decrease")) << e;
	// the odometry noise options
	// the odometry noise options (a fresh INI each: CConfigFileMemory::setContent merges)
	auto noiseError = [](const std::string& text)
	{
		const mrpt::config::CConfigFileMemory ini(text);
		TOdometryNoiseOptions n;
		try
		{
			n.loadFromConfigFile(ini, "OdometryNoise");
		}
		catch (const std::invalid_argument& x)
		{
			return std::string(x.what());
		}
		return std::string();
	};
	EXPECT_TRUE(contains(noiseError("[OdometryNoise]\na1 = -1\n"), "[OdometryNoise] a1"));
	EXPECT_TRUE(contains(noiseError("[OdometryNoise]\nminStdXYZ = 1\n"), "minStdXYZ: unknown key"));
	EXPECT_TRUE(contains(noiseError("[OdometryNoise]\nmodel = thrun\n"), "[OdometryNoise] model"));
	EXPECT_EQ(noiseError("[OdometryNoise]\nminStdPHI_deg = 2\n"), "");
	TOdometryNoiseOptions n;
	n.loadFromConfigFile(mrpt::config::CConfigFileMemory("[OdometryNoise]\nminStdPHI_deg = 2\n"),
	                     "OdometryNoise");
	EXPECT_NEAR(n.minStdPHI, 2 * M_PI / 180, 1e-15);
}

TEST(RawlogIO, NanSensorPoseInFormat1IsRejected)
{
	const TRawlog h = loadRawlog(dataset("highway.rawlog"));
	const std::string p = apps_test::freshDir("nan1") + "/nan.rawlog";
	{
		mrpt::io::CFileGZOutputStream f(p);
		auto ar = mrpt::serialization::archiveFrom(f);
		for (size_t k = 0; k < 3; ++k)
		{
			auto sf = mrpt::obs::CSensoryFrame::Create();
			auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
			    *h.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>());
			if (k == 2) obs->sensorLocationOnRobot.x(std::numeric_limits<double>::quiet_NaN());
			sf->insert(obs);
			ar << *h.actions[k] << *sf;
		}
	}
	const std::string e = loadError(p);
	EXPECT_TRUE(contains(e, p + "': entry 5")) << e;
	EXPECT_TRUE(contains(e, "sensorLocationOnRobot is not finite")) << e;
}

// ---------------------------------------------------------------------------------------
// What MRPT 2.5.8 does to an emOdometry action on reading (doc/simulator.md, doc/apps.md)
// ---------------------------------------------------------------------------------------
namespace
{
mrpt::poses::CPosePDFGaussian roundTrip(const mrpt::obs::CActionRobotMovement2D& a)
{
	mrpt::io::CMemoryStream m;
	auto ar = mrpt::serialization::archiveFrom(m);
	ar << a;
	m.Seek(0);
	const auto b = std::dynamic_pointer_cast<mrpt::obs::CActionRobotMovement2D>(ar.ReadObject());
	return mrpt::poses::CPosePDFGaussian(*b->poseChange);
}
}  // namespace

TEST(MrptActions, EmOdometryCovarianceIsRebuiltFromTheStoredMotionModel)
{
	using mrpt::obs::CActionRobotMovement2D;
	const mrpt::poses::CPose2D u(1, 0, 0);
	mrpt::math::CMatrixDouble33 C;
	C.setZero();
	C(0, 0) = C(1, 1) = 1e-5;
	C(2, 2) = 1e-7;
	// 1) poseChange set directly, estimationMethod = emOdometry: the file keeps the raw
	//    increment and the motion-model options (here MRPT's defaults), and reading rebuilds the
	//    covariance from them: the writer's 1e-5 is lost.
	CActionRobotMovement2D a;
	a.estimationMethod = CActionRobotMovement2D::emOdometry;
	a.rawOdometryIncrementReading = u;
	a.poseChange = mrpt::poses::CPosePDFGaussian::Create(u, C);
	const auto ga = roundTrip(a);
	CActionRobotMovement2D def;
	def.computeFromOdometry(u, CActionRobotMovement2D::TMotionModelOptions());
	const mrpt::poses::CPosePDFGaussian gd(*def.poseChange);
	std::printf(
	    "[  info    ] emOdometry written with cov(0,0) = 1e-5, read back: %.6g (MRPT's "
	    "default model: %.6g)\n",
	    ga.cov(0, 0), gd.cov(0, 0));
	// (the options are stored as float: 1e-9 is float rounding, far below the 1e-5 at stake)
	EXPECT_NEAR(ga.cov(0, 0), gd.cov(0, 0), 1e-9);
	EXPECT_NEAR(ga.cov(2, 2), gd.cov(2, 2), 1e-9);
	EXPECT_GT(ga.cov(0, 0), 10 * C(0, 0));
	// 2) computeFromOdometry with the writer's own options (what simul-landmarks does): the
	//    rebuild uses the stored options, so the writer's model survives.
	CActionRobotMovement2D::TMotionModelOptions o;
	o.gaussianModel = {0, 0, 0, 0, 0.04, 0.01};
	CActionRobotMovement2D b;
	b.computeFromOdometry(u, o);
	const auto gb = roundTrip(b);
	EXPECT_NEAR(gb.cov(0, 0), 0.04 * 0.04, 1e-9);
	EXPECT_NEAR(gb.cov(2, 2), 0.01 * 0.01, 1e-9);
	// 3) Any other method (dynslam-simulate, dynslam-mrclam: emScan2DMatching) stores the PDF.
	CActionRobotMovement2D c = a;
	c.estimationMethod = CActionRobotMovement2D::emScan2DMatching;
	const auto gc = roundTrip(c);
	EXPECT_EQ(gc.cov(0, 0), 1e-5);
	EXPECT_EQ(gc.cov(2, 2), 1e-7);
}
