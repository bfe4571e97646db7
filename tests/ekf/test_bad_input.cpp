/** Bad input: a clear error (state unchanged) or a documented, counted skip; never a crash. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <limits>

#include "tiny_scenario.h"

using namespace dynslam;
using mrpt::obs::CObservationBearingRange;

namespace
{
struct Fixture
{
	CDynamicKFSLAM2D f;
	dynslam_test::TinyScenario sc;
	Fixture()
	{
		dynslam_test::TinyScenarioOptions o;
		o.objects = 1;
		o.steps = 6;
		sc = dynslam_test::makeTinyScenario(o);
		f.options.measurement_model = models::MeasurementModel::RangeBearing;
		f.options.Sigma_v = o.Sigma_rb;
		f.reset();
		for (size_t k = 0; k < 3; ++k) f.processActionObservation(sc.actions[k], sc.frames[k]);
	}
	/** A frame with one range-bearing observation holding the given measurements. */
	static mrpt::obs::CSensoryFrame::Ptr frame(
	    const std::vector<CObservationBearingRange::TMeasurement>& ms)
	{
		auto obs = CObservationBearingRange::Create();
		obs->maxSensorDistance = 12;
		obs->sensedData = ms;
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		return sf;
	}
	static CObservationBearingRange::TMeasurement meas(int32_t id, float r, float yaw,
	                                                   float pitch = 0)
	{
		CObservationBearingRange::TMeasurement m;
		m.landmarkID = id;
		m.range = r;
		m.yaw = yaw;
		m.pitch = pitch;
		return m;
	}
	/** Expects a throw whose message contains `what`, and an unchanged filter. */
	void expectRejected(const mrpt::obs::CActionCollection::Ptr& a,
	                    const mrpt::obs::CSensoryFrame::Ptr& sf, const std::string& what)
	{
		const Eigen::VectorXd x0 = f.fullMean().asEigen();
		const Eigen::MatrixXd P0 = f.fullCov().asEigen();
		const size_t slots0 = f.getSlots().size();
		const int step0 = f.stepCount();
		try
		{
			f.processActionObservation(a, sf);
			ADD_FAILURE() << "no exception for: " << what;
		}
		catch (const std::runtime_error& e)
		{
			EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
		}
		EXPECT_EQ(f.fullMean().asEigen(), x0);
		EXPECT_EQ(f.fullCov().asEigen(), P0);
		EXPECT_EQ(f.getSlots().size(), slots0);
		EXPECT_EQ(f.stepCount(), step0);
	}
};
const auto zeroAction = []
{
	return dynslam_test::makeAction(Eigen::Vector3d(0.1, 0, 0), Eigen::Matrix3d::Identity() * 1e-6);
};
}  // namespace

TEST(DynamicBadInput, NanOrInfInObservation)
{
	Fixture t;
	t.expectRejected(zeroAction(), Fixture::frame({Fixture::meas(1, std::nanf(""), 0.1f)}),
	                 "NaN or Inf");
	t.expectRejected(zeroAction(),
	                 Fixture::frame({Fixture::meas(1, 3, std::numeric_limits<float>::infinity())}),
	                 "NaN or Inf");
}

TEST(DynamicBadInput, NanInOdometry)
{
	Fixture t;
	auto a = dynslam_test::makeAction(Eigen::Vector3d(std::nan(""), 0, 0),
	                                  Eigen::Matrix3d::Identity() * 1e-6);
	t.expectRejected(a, Fixture::frame({}), "not finite");
}

TEST(DynamicBadInput, DuplicateIdsInOneObservation)
{
	Fixture t;
	t.expectRejected(zeroAction(),
	                 Fixture::frame({Fixture::meas(3, 5, 0.1f), Fixture::meas(3, 6, 0.2f)}),
	                 "duplicate");
}

TEST(DynamicBadInput, UnknownIdRange)
{
	// -1 is MRPT's unknown landmark: associated, never rejected (issue 30;
	// test_mrpt_conventions.cpp); -7 is in no range.
	Fixture t;
	t.expectRejected(zeroAction(), Fixture::frame({Fixture::meas(-7, 5, 0.1f)}),
	                 "no known ID range");
}

TEST(DynamicBadInput, NonZeroPitchAndZeroRange)
{
	Fixture t;
	t.expectRejected(zeroAction(), Fixture::frame({Fixture::meas(2, 5, 0.1f, 0.2f)}), "pitch");
	t.expectRejected(zeroAction(), Fixture::frame({Fixture::meas(2, 0, 0.1f)}), "zero range");
}

TEST(DynamicBadInput, SensorPoseNotFiniteOrTilted)
{
	// A NaN / Inf in sensorLocationOnRobot names the field and the values; a tilted sensor
	// (pitch or roll) is rejected: 2-D SLAM. The filter is unchanged.
	Fixture t;
	const double nan = std::numeric_limits<double>::quiet_NaN();
	const double inf = std::numeric_limits<double>::infinity();
	for (int i : {0, 1, 2})
	{
		auto sf = Fixture::frame({Fixture::meas(2, 5, 0.1f)});
		auto& p = sf->getObservationByClass<CObservationBearingRange>()->sensorLocationOnRobot;
		if (i == 0) p.x(nan);
		if (i == 1) p.y(inf);
		if (i == 2) p.z(nan);
		t.expectRejected(zeroAction(), sf, "sensorLocationOnRobot is not finite (x y z yaw");
	}
	for (const auto& [pitch, roll] : std::vector<std::pair<double, double>>{{0.1, 0}, {0, -0.05}})
	{
		auto sf = Fixture::frame({Fixture::meas(2, 5, 0.1f)});
		sf->getObservationByClass<CObservationBearingRange>()->sensorLocationOnRobot =
		    mrpt::poses::CPose3D(0.3, 0, 0, 0.2, pitch, roll);
		t.expectRejected(zeroAction(), sf, "non-zero pitch or roll");
	}
}

TEST(DynamicBadInput, SensorHeightIsIgnoredAsInMrpt)
{
	// A sensor above the robot (z only) is 2-D: the readings lie in its horizontal plane. The
	// filter gives exactly what it gives with z = 0 (MRPT's CRangeBearingKFSLAM2D takes
	// CPose2D(sensorLocationOnRobot) too).
	Fixture a, b;
	for (size_t k = 3; k < a.sc.actions.size(); ++k)
	{
		auto sa = mrpt::obs::CSensoryFrame::Create(), sb = mrpt::obs::CSensoryFrame::Create();
		auto oa = std::make_shared<CObservationBearingRange>(
		    *a.sc.frames[k]->getObservationByClass<CObservationBearingRange>());
		auto ob = std::make_shared<CObservationBearingRange>(*oa);
		oa->sensorLocationOnRobot = mrpt::poses::CPose3D(0.3, -0.1, 0.0, 0.2, 0, 0);
		ob->sensorLocationOnRobot = mrpt::poses::CPose3D(0.3, -0.1, 1.5, 0.2, 0, 0);
		sa->insert(oa);
		sb->insert(ob);
		a.f.processActionObservation(a.sc.actions[k], sa);
		b.f.processActionObservation(b.sc.actions[k], sb);
		EXPECT_EQ(a.f.fullMean().asEigen(), b.f.fullMean().asEigen()) << "step " << k;
		EXPECT_EQ(a.f.fullCov().asEigen(), b.f.fullCov().asEigen()) << "step " << k;
	}
}

TEST(DynamicBadInput, WrongActionType)
{
	Fixture t;
	auto acts = mrpt::obs::CActionCollection::Create();
	mrpt::obs::CActionRobotMovement3D m3;
	acts->insert(m3);
	t.expectRejected(acts, Fixture::frame({}), "no CActionRobotMovement2D");
	// An empty action collection is MRPT's step without odometry (stds_Q_no_odo), not an error
	// (issue 30; MrptConventions.AStepWithoutOdometryUsesStdsQNoOdoAsMrptDoes).
	t.expectRejected(nullptr, Fixture::frame({}), "null action");
	t.expectRejected(zeroAction(), nullptr, "null sensory frame");
}

TEST(DynamicBadInput, StepWithoutObservationIsOdometryOnly)
{
	Fixture t;
	const double varBefore = t.f.fullCov()(0, 0);
	t.f.processActionObservation(zeroAction(), mrpt::obs::CSensoryFrame::Create());
	EXPECT_GT(t.f.fullCov()(0, 0), varBefore);
}

TEST(DynamicBadInput, ObjectWithIdenticalFeaturesIsSkippedAndCounted)
{
	// All three features of object 5 at the same point: the rotation is undetermined.
	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
	f.reset();
	size_t skipped = 0;
	for (int k = 0; k < 4; ++k)
	{
		std::vector<CObservationBearingRange::TMeasurement> ms{Fixture::meas(1, 4, 0.3f)};
		for (int j = 0; j < 3; ++j)
			ms.push_back(Fixture::meas(ids::objectFeatureId(5, j), 6 + 0.1f * k, -0.2f));
		f.processActionObservation(zeroAction(), Fixture::frame(ms));
		skipped += f.getLastStepReport().skipped_pose_degenerate;
		EXPECT_TRUE(f.fullCov().asEigen().allFinite());
	}
	EXPECT_EQ(skipped, 3u);  // every step after the first sighting
	EXPECT_TRUE(f.getObjectTracks().at(5).poses.empty());
}

TEST(DynamicBadInput, CollinearFeaturesAreFineIn2D)
{
	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = Eigen::Matrix2d::Identity() * 1e-6;
	f.reset();
	for (int k = 0; k < 3; ++k)
	{
		std::vector<CObservationBearingRange::TMeasurement> ms{Fixture::meas(1, 4, 0.3f)};
		for (int j = 0; j < 3; ++j)
		{
			const Eigen::Vector2d p(5.0 + j + 0.2 * k, 1.0);  // three collinear points, moving
			const Eigen::Vector2d rb = models::cartesianToRangeBearing(p);
			ms.push_back(Fixture::meas(ids::objectFeatureId(2, j), float(rb[0]), float(rb[1])));
		}
		f.processActionObservation(
		    dynslam_test::makeAction(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()),
		    Fixture::frame(ms));
		EXPECT_EQ(f.getLastStepReport().skipped_pose_degenerate, 0u);
	}
	const auto poses = f.getObjectTracks().at(2).poses;
	ASSERT_EQ(poses.size(), 2u);  // steps 1 and 2; the step-1 pose was dropped (K = 1) and recorded
	EXPECT_FALSE(poses[0].in_state);
	EXPECT_TRUE(poses[1].in_state);
	EXPECT_NEAR(poses[1].mean[0], 0.4, 1e-4);
	EXPECT_NEAR(poses[1].mean[1], 0.0, 1e-4);
	EXPECT_NEAR(poses[1].mean[2], 0.0, 1e-4);
}

TEST(DynamicBadInput, FeatureNotSeenAtTimeZeroIsSkippedAndCounted)
{
	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
	f.reset();
	const auto a = dynslam_test::makeAction(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
	f.processActionObservation(
	    a, Fixture::frame({Fixture::meas(ids::objectFeatureId(1, 0), 5, 0.1f),
	                       Fixture::meas(ids::objectFeatureId(1, 1), 5, 0.3f)}));
	f.processActionObservation(
	    a, Fixture::frame({Fixture::meas(ids::objectFeatureId(1, 0), 5, 0.1f),
	                       Fixture::meas(ids::objectFeatureId(1, 1), 5, 0.3f),
	                       Fixture::meas(ids::objectFeatureId(1, 2), 5, 0.5f)}));
	EXPECT_EQ(f.getLastStepReport().skipped_unknown_object_feature, 1u);
	EXPECT_EQ(f.getLastStepReport().object_poses_added, 1u);
}

TEST(DynamicBadInput, IdAboveLastObjectIsInvalid)
{
	static_assert(ids::classify(INT32_MAX) == ids::IdKind::Invalid);
	static_assert(ids::classify(ids::kObjectBase + ids::kMaxObject * ids::kFeaturesPerObject +
	                            999) == ids::IdKind::ObjectFeature);
	Fixture t;
	t.expectRejected(zeroAction(), Fixture::frame({Fixture::meas(INT32_MAX, 5, 0.1f)}),
	                 "no known ID range");
}

TEST(DynamicBadInput, NumericalFailureMidStepIsReportedAndBlocksUntilReset)
{
	// Noise settings that validate() accepts but that break the update numerically (found by
	// fuzzing): S = H P H^T + R is not positive definite in floating point.
	dynslam_test::TinyScenarioOptions o;
	o.steps = 8;
	const auto sc = dynslam_test::makeTinyScenario(o);
	CDynamicKFSLAM2D f;
	f.options.measurement_model = models::MeasurementModel::RangeBearing;
	f.options.Sigma_v = Eigen::Vector2d(1e65, 1e-5).asDiagonal();
	f.reset();
	bool failed = false;
	for (size_t k = 0; k < sc.actions.size() && !failed; ++k)
	{
		try
		{
			f.processActionObservation(sc.actions[k], sc.frames[k]);
		}
		catch (const std::runtime_error& e)
		{
			failed = true;
			EXPECT_NE(std::string(e.what()).find("must be reset"), std::string::npos) << e.what();
		}
	}
	ASSERT_TRUE(failed) << "the extreme setting no longer fails: pick another trigger";
	try
	{
		f.processActionObservation(sc.actions[0], sc.frames[0]);
		ADD_FAILURE() << "a failed filter must refuse further steps";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("call reset()"), std::string::npos) << e.what();
	}
	f.options.Sigma_v = o.Sigma_rb;
	f.reset();
	for (size_t k = 0; k < sc.actions.size(); ++k)
		f.processActionObservation(sc.actions[k], sc.frames[k]);
	EXPECT_TRUE(f.fullCov().asEigen().allFinite());
}
