/** The static baseline adapter around mrpt::slam::CRangeBearingKFSLAM2D: input modes,
 * results, strict R options. */
#include <apps_test_utils.h>
#include <dynslam/apps/CStaticBaselineBackend.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/landmark_ids.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <set>

using namespace dynslam;
using namespace dynslam::apps;

namespace
{
const char* kIni = R"([RangeBearingKFSLAM]
std_sensor_range   = 0.0031622776601683794
std_sensor_yaw_deg = 0.0065885514027692127
[RangeBearingKFSLAM_KalmanFilter]
method = kfEKFNaive
verbosity_level = LVL_ERROR
)";
}

TEST(StaticBaseline, StaticOnlyModeRemovesExactlyTheObjectFeatures)
{
	const TRawlog r = loadRawlog(apps_test::dataset("highway.rawlog"));
	size_t objectReadings = 0;
	std::set<int32_t> staticIds, objectIds;
	for (const auto& sf : r.frames)
		for (const auto& m :
		     sf->getObservationByClass<mrpt::obs::CObservationBearingRange>()->sensedData)
			if (ids::isStatic(m.landmarkID))
				staticIds.insert(m.landmarkID);
			else
				++objectReadings, objectIds.insert(m.landmarkID);
	ASSERT_GT(objectReadings, 0u);

	mrpt::config::CConfigFileMemory ini(kIni);
	CStaticBaselineBackend only(CStaticBaselineBackend::Mode::StaticOnly);
	only.loadOptions(ini);
	CStaticBaselineBackend all(CStaticBaselineBackend::Mode::AllFeatures);
	all.loadOptions(ini);
	EXPECT_EQ(only.name(), "static_landmarks_only");
	EXPECT_EQ(all.name(), "static_all");
	const TFilterRun ro = runFilter(only, r.actions, r.frames);
	const TFilterRun ra = runFilter(all, r.actions, r.frames);
	EXPECT_EQ(only.removedReadings(), objectReadings);
	EXPECT_EQ(all.removedReadings(), 0u);

	// The static-only map holds exactly the static IDs; the naive one also the moving features.
	std::set<int32_t> mo, ma;
	for (const auto& l : ro.est.landmarks) mo.insert(l.id);
	for (const auto& l : ra.est.landmarks) ma.insert(l.id);
	EXPECT_EQ(mo, staticIds);
	std::set<int32_t> both = staticIds;
	both.insert(objectIds.begin(), objectIds.end());
	EXPECT_EQ(ma, both);
	// Joint covariance in the order of the landmarks, symmetric.
	ASSERT_EQ(ro.est.landmarks_cov.rows(), Eigen::Index(2 * ro.est.landmarks.size()));
	EXPECT_LT((ro.est.landmarks_cov - ro.est.landmarks_cov.transpose()).cwiseAbs().maxCoeff(),
	          1e-12);
	EXPECT_DOUBLE_EQ(ro.est.landmarks_cov(0, 0), ro.est.landmarks[0].cov(0, 0));
	// The caller's data are untouched by the static-only mode.
	size_t after = 0;
	for (const auto& sf : r.frames)
		for (const auto& m :
		     sf->getObservationByClass<mrpt::obs::CObservationBearingRange>()->sensedData)
			after += ids::isObjectFeature(m.landmarkID);
	EXPECT_EQ(after, objectReadings);
	EXPECT_EQ(ro.est.ego.size(), r.size());
}

TEST(StaticBaseline, RValuesAreRequiredAndPositive)
{
	auto err = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory ini(text);
		CStaticBaselineBackend b(CStaticBaselineBackend::Mode::AllFeatures);
		try
		{
			b.loadOptions(ini);
		}
		catch (const std::exception& e)
		{
			return std::string(e.what());
		}
		return std::string();
	};
	const std::string noRange = err("[RangeBearingKFSLAM]\nstd_sensor_yaw_deg = 0.1\n");
	EXPECT_NE(noRange.find("[RangeBearingKFSLAM] std_sensor_range"), std::string::npos) << noRange;
	const std::string neg =
	    err("[RangeBearingKFSLAM]\nstd_sensor_range = -1\nstd_sensor_yaw_deg = 0.1\n");
	EXPECT_NE(neg.find("std_sensor_range = '-1'"), std::string::npos) << neg;
	const std::string ikf =
	    err(std::string(kIni) + "[RangeBearingKFSLAM_KalmanFilter]\nmethod = kfIKF\n");
	EXPECT_NE(ikf.find("method"), std::string::npos) << ikf;
	EXPECT_EQ(err(kIni), "");
}

TEST(StaticBaseline, FactoryKnowsEveryKind)
{
	mrpt::config::CConfigFileMemory ini(kIni);
	EXPECT_EQ(makeBackend("static_all", ini)->name(), "static_all");
	EXPECT_EQ(makeBackend("static_landmarks_only", ini)->name(), "static_landmarks_only");
	try
	{
		makeBackend("ukf", ini);
		FAIL();
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("unknown back-end 'ukf'"), std::string::npos);
	}
}

TEST(StaticBaseline, MixedUnknownAndLabelledIdsAreAnErrorNamingTheReading)
{
	// Issue 12: clutter with clutter_ids = unknown (-1) next to labelled readings. MRPT's
	// CRangeBearingKFSLAM2D would throw "Duplicated `key`" a few steps later from its bimap.
	const TRawlog r = loadRawlog(apps_test::dataset("highway.rawlog"));
	mrpt::config::CConfigFileMemory ini(kIni);
	CStaticBaselineBackend all(CStaticBaselineBackend::Mode::AllFeatures);
	all.loadOptions(ini);
	all.processActionObservation(r.actions[0], r.frames[0]);
	auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
	    *r.frames[1]->getObservationByClass<mrpt::obs::CObservationBearingRange>());
	obs->sensedData[2].landmarkID = -1;
	auto sf = mrpt::obs::CSensoryFrame::Create();
	sf->insert(obs);
	try
	{
		all.processActionObservation(r.actions[1], sf);
		ADD_FAILURE() << "a -1 ID among labelled readings was accepted";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("step 1: measurement 2 (landmark ID -1)"),
		          std::string::npos)
		    << e.what();
	}
	// static_landmarks_only removes the -1 reading and counts it.
	CStaticBaselineBackend only(CStaticBaselineBackend::Mode::StaticOnly);
	only.loadOptions(ini);
	only.processActionObservation(r.actions[0], r.frames[0]);
	const size_t before = only.removedReadings();
	only.processActionObservation(r.actions[1], sf);
	size_t objects = 0;
	for (const auto& m : obs->sensedData) objects += ids::isObjectFeature(m.landmarkID);
	EXPECT_EQ(only.removedReadings() - before, objects + 1);
}
