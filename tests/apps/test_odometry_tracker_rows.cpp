/** The `odometry` and `tracker_baseline` rows of dynslam-compare (CDeadReckoningBackend,
 * CTrackerBaselineBackend; issue 31) through the apps' factory makeBackend:
 * - odometry: the ego equals MRPT's own composition of Gaussian poses (CPosePDFGaussian +=,
 *   the first-order propagation) of the increments, mean and covariance;
 * - tracker_baseline on a synthetic two-car sequence (the ego driving 1 m per 0.1 s step; car A
 *   parked at (10, 3), car B driving 0.5 m per step at y = -3), boxes in the DETECTION_BOXES
 *   comment (dynslam/common/detection_boxes.h): the IDs, AB3DMOT's output rule (the first min_hits
 *   steps, Lost tracks with report_lost, deletion after max_age = 2 misses, a new ID on
 *   return), and the reported poses in the robot frame;
 * - bad input: boxes without a time stamp, [BoxTracker] keys. */
#include <dynslam/apps/CTrackerBaselineBackend.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/common/detection_boxes.h>
#include <dynslam/common/detection_groups.h>
#include <dynslam/common/odometry_action.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

using namespace dynslam;

namespace
{
mrpt::Clock::time_point stampOf(int k) { return mrpt::Clock::fromDouble(1000.0 + 0.1 * k); }

/** A step's sensory frame as doc/formats.md writes boxes: the range-bearing observation with
 * each box's four corners (ID -1), the DETECTION_GROUPS and the DETECTION_BOXES comments. */
mrpt::obs::CSensoryFrame::Ptr frame(const std::vector<estimator::TBoxDetection>& boxes)
{
	auto SF = mrpt::obs::CSensoryFrame::Create();
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	obs->maxSensorDistance = 50;
	std::vector<int32_t> ids, groups;
	for (const estimator::TBoxDetection& b : boxes)
		for (const Eigen::Vector2d& c : boxCorners(b))
		{
			mrpt::obs::CObservationBearingRange::TMeasurement m;
			m.range = float(c.norm());
			m.yaw = float(std::atan2(c.y(), c.x()));
			m.pitch = 0;
			m.landmarkID = -1;
			obs->sensedData.push_back(m);
			ids.push_back(-1);
			groups.push_back(b.group);
		}
	SF->insert(obs);
	if (boxes.empty()) return SF;
	SF->insert(makeDetectionGroups(ids, groups));
	SF->insert(makeDetectionBoxes(boxes));
	return SF;
}

estimator::TBoxDetection det(int group, double x, double y, double yaw, double score = 0.9)
{
	estimator::TBoxDetection b;
	b.group = group;
	b.cls = "Car";
	b.score = score;
	b.pose << x, y, yaw;
	b.extent << 4, 2;
	return b;
}

std::unique_ptr<ISlamBackend> backend(const std::string& kind, const std::string& ini = "")
{
	mrpt::config::CConfigFileMemory c(ini);
	return apps::makeBackend(kind, c);
}
}  // namespace

TEST(OdometryRow, EgoIsTheComposedIncrementsAndCovariance)
{
	auto b = backend("odometry");
	EXPECT_EQ(b->name(), "odometry");
	mrpt::poses::CPosePDFGaussian ref;  // (0, 0, 0), zero covariance
	for (int k = 0; k < 6; ++k)
	{
		const Eigen::Vector3d u(1.0 + 0.1 * k, 0.05 * k - 0.1, 0.2 - 0.07 * k);
		Eigen::Matrix3d U;
		U << 0.01 + 0.001 * k, 0.002, 0.0001, 0.002, 0.004, 0.0002, 0.0001, 0.0002, 0.0009;
		b->processActionObservation(makeOdometryAction(u, U, stampOf(k)), frame({}));
		ref += mrpt::poses::CPosePDFGaussian(mrpt::poses::CPose2D(u.x(), u.y(), u.z()),
		                                     mrpt::math::CMatrixDouble33(U));
		const mrpt::poses::CPosePDFGaussian e = b->getEgoPose();
		EXPECT_NEAR(e.mean.x(), ref.mean.x(), 1e-12) << k;
		EXPECT_NEAR(e.mean.y(), ref.mean.y(), 1e-12) << k;
		EXPECT_NEAR(e.mean.phi(), ref.mean.phi(), 1e-12) << k;
		EXPECT_LT((e.cov.asEigen() - ref.cov.asEigen()).norm(), 1e-12) << k;
		EXPECT_EQ(b->getLastStepReport().step, k);
	}
	EXPECT_GT(b->getEgoPose().cov(0, 0), 0.05);  // it grows: 6 increments of >= 0.01 m^2
	EXPECT_TRUE(b->getStaticLandmarks().empty());
	EXPECT_TRUE(b->getObjectTracks().empty());
	EXPECT_TRUE(b->trackedBoxes().empty());
}

TEST(TrackerBaselineRow, TwoCarsIdsOutputRuleAndPoses)
{
	for (const bool reportLost : {true, false})
	{
		auto b = backend("tracker_baseline", std::string("[BoxTracker]\nreport_lost = ") +
		                                         (reportLost ? "true" : "false"));
		// A seen in steps 0-4, missed in 5 and 6 (deleted at the 2nd miss), back in step 7
		for (int k = 0; k < 8; ++k)
		{
			const double ego = 1.0 * k;  // the ego's x after step k's increment
			std::vector<estimator::TBoxDetection> boxes;
			const bool seesA = k <= 4 || k == 7;
			if (seesA) boxes.push_back(det(0, 10 - ego, 3, 0.1));
			boxes.push_back(det(1, 5 + 0.5 * k - ego, -3, 0));
			b->processActionObservation(
			    makeOdometryAction(Eigen::Vector3d(k == 0 ? 0 : 1, 0, 0),
			                       1e-4 * Eigen::Matrix3d::Identity(), stampOf(k)),
			    frame(boxes));
			const std::vector<TTrackedBox> out = b->trackedBoxes();
			std::optional<TTrackedBox> a, c;
			for (const TTrackedBox& t : out) (t.track == 1 ? c : a) = t;
			// B: track 1 in every step (steps 0-2: AB3DMOT's first min_hits frames; then
			// confirmed and updated); it moves 0.5 m per step: the filter lags less than the
			// box's half length
			ASSERT_TRUE(c.has_value()) << k;
			EXPECT_LT(std::hypot(c->pose.x() - (5 + 0.5 * k - ego), c->pose.y() + 3), 2.0) << k;
			EXPECT_EQ(c->cls, "Car");
			EXPECT_DOUBLE_EQ(c->score, 0.9);
			// A: track 0 while seen (parked, boxes exact: its pose is the box's in the robot
			// frame), Lost in step 5 (reported with report_lost), deleted in step 6; in step 7
			// a new Tentative track (ID 2) not yet reported (step 8 > min_hits)
			if (k <= 4 || (k == 5 && reportLost))
			{
				ASSERT_TRUE(a.has_value()) << k;
				EXPECT_EQ(a->track, 0) << k;
				EXPECT_NEAR(a->pose.x(), 10 - ego, 1e-9) << k;
				EXPECT_NEAR(a->pose.y(), 3, 1e-9) << k;
				EXPECT_NEAR(a->pose.z(), 0.1, 1e-9) << k;
				EXPECT_NEAR(a->extent.x(), 4, 1e-9);
			}
			else
				EXPECT_FALSE(a.has_value()) << k << " track " << a->track;
			EXPECT_EQ(out.size(), size_t(1 + (a ? 1 : 0))) << k;
		}
		const auto* tb = dynamic_cast<const apps::CTrackerBaselineBackend*>(b.get());
		ASSERT_NE(tb, nullptr);
		ASSERT_EQ(tb->tracker().tracks().size(), 2u);
		EXPECT_EQ(tb->tracker().tracks()[1].id, 2);  // A's return: a new ID
		EXPECT_EQ(tb->tracker().tracks()[1].state, estimator::ETrackState::Tentative);
	}
}

TEST(TrackerBaselineRow, FirstFramesRuleOnBothSides)
{
	// one car seen in steps 0 and 1 only: Tentative; reported in step 1 (<= min_hits = 3)
	// with report_first_frames, not without
	for (const bool first : {true, false})
	{
		auto b = backend("tracker_baseline", std::string("[BoxTracker]\nreport_first_frames = ") +
		                                         (first ? "true" : "false"));
		for (int k = 0; k < 2; ++k)
			b->processActionObservation(
			    makeOdometryAction(Eigen::Vector3d::Zero(), 1e-4 * Eigen::Matrix3d::Identity(),
			                       stampOf(k)),
			    frame({det(0, 8, 0, 0)}));
		EXPECT_EQ(b->trackedBoxes().size(), first ? 1u : 0u);
	}
}

TEST(TrackerBaselineRow, BadInput)
{
	auto b = backend("tracker_baseline");
	EXPECT_THROW(b->processActionObservation(makeOdometryAction(Eigen::Vector3d::Zero(),
	                                                            1e-4 * Eigen::Matrix3d::Identity()),
	                                         frame({det(0, 8, 0, 0)})),
	             std::runtime_error);  // boxes but no time stamp
	EXPECT_THROW(backend("tracker_baseline", "[BoxTracker]\nmin_hit = 3"), std::invalid_argument);
	EXPECT_THROW(backend("tracker_baseline", "[BoxTracker]\nmin_hits = 0"), std::invalid_argument);
	EXPECT_THROW(backend("tracker_baseline", "[BoxTracker]\nmetric = iou3d"),
	             std::invalid_argument);
	EXPECT_THROW(backend("tracker_baseline", "[BoxTracker]\nmeas_std = [1 2 3]"),
	             std::invalid_argument);
	try
	{
		backend("tracker_baseline", "[BoxTracker]\nbirth_window = 2");  // < min_hits 3
		ADD_FAILURE() << "no throw";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("[BoxTracker]"), std::string::npos) << e.what();
		EXPECT_NE(std::string(e.what()).find("birth_window"), std::string::npos) << e.what();
	}
	// the defaults: AB3DMOT's (bev_iou 0.01, min_hits 3, max_age 2, window 5)
	TBoxTrackerOptions o;
	EXPECT_EQ(o.params.metric, "bev_iou");
	EXPECT_EQ(o.params.min_iou, 0.01);
	EXPECT_EQ(o.params.min_hits, 3);
	EXPECT_EQ(o.params.max_age, 2);
	EXPECT_EQ(o.params.birth_window, 5);
	std::ostringstream dump;
	o.dumpToTextStream(dump);
	EXPECT_NE(dump.str().find("birth_window                   = 5"), std::string::npos);
}
