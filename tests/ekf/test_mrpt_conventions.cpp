/** Readings with MRPT's "unknown landmark" ID -1 under the default feature_labels = ids (issue
 * 30, item 1): associated as CRangeBearingKFSLAM2D associates them (data_association_full_
 * covariance, assocNN, metricMaha, chi-square 0.99), never an error. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/unknown_id_association.h>
#include <gtest/gtest.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <set>

#include "tiny_scenario.h"

using namespace dynslam;

namespace
{
/** A copy of the scenario's frames with every landmark ID replaced by -1 (keepFirst: the
 * first reading of each landmark keeps its ID). */
std::vector<mrpt::obs::CSensoryFrame::Ptr> anonymous(const dynslam_test::TinyScenario& sc,
                                                     bool keepFirst)
{
	std::vector<mrpt::obs::CSensoryFrame::Ptr> out;
	std::set<int32_t> seen;
	for (const auto& f : sc.frames)
	{
		auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
		    *f->getObservationByClass<mrpt::obs::CObservationBearingRange>());
		for (auto& m : obs->sensedData)
			if (!keepFirst || !seen.insert(m.landmarkID).second) m.landmarkID = -1;
		auto sf = mrpt::obs::CSensoryFrame::Create();
		sf->insert(obs);
		out.push_back(sf);
	}
	return out;
}

dynslam_test::TinyScenarioOptions scenario(unsigned seed)
{
	dynslam_test::TinyScenarioOptions o;
	o.steps = 40;
	o.landmarks = 15;
	o.seed = seed;
	return o;
}
}  // namespace

TEST(MrptConventions, UnknownIdsEveryReadingMinusOneEqualsMrpt)
{
	// Every reading -1: MRPT's filter associates each with its predictions or adds a landmark;
	// ours (range-bearing model, MRPT's start) must give the same map, in the same order, and
	// the same mean and covariance.
	for (unsigned seed : {1u, 2u})
	{
		const auto sc = dynslam_test::makeTinyScenario(scenario(seed));
		const auto frames = anonymous(sc, false);
		mrpt::slam::CRangeBearingKFSLAM2D rb;
		rb.options.std_sensor_range = 0.01f;
		rb.options.std_sensor_yaw = 0.001f;
		rb.setMinLoggingLevel(mrpt::system::LVL_ERROR);
		CDynamicKFSLAM2D dyn;
		dyn.options.measurement_model = models::MeasurementModel::RangeBearing;
		const float sr = rb.options.std_sensor_range, sy = rb.options.std_sensor_yaw;
		dyn.options.Sigma_v = Eigen::Vector2d(double(sr * sr), double(sy * sy)).asDiagonal();
		dyn.options.Sigma_0.setZero();
		dyn.options.skip_prediction_on_empty_map = true;
		dyn.reset();
		size_t associated = 0, created = 0;
		double worst = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			auto a = sc.actions[k];
			auto f = frames[k];
			rb.processActionObservation(a, f);
			ASSERT_NO_THROW(dyn.processActionObservation(a, f)) << "step " << k;
			associated += dyn.getLastStepReport().unknown_id_associated;
			created += dyn.getLastStepReport().unknown_id_new;
			EXPECT_EQ(dyn.getLastStepReport().skipped_unknown_id, 0u);
			mrpt::poses::CPosePDFGaussian pose;
			std::vector<mrpt::math::TPoint2D> lms;
			std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
			mrpt::math::CVectorDouble x;
			mrpt::math::CMatrixDouble P;
			rb.getCurrentState(pose, lms, ids, x, P);
			ASSERT_EQ(size_t(x.size()), size_t(dyn.fullMean().size())) << "step " << k;
			const Eigen::VectorXd dx = x.asEigen() - dyn.fullMean().asEigen();
			const Eigen::MatrixXd dP = P.asEigen() - dyn.fullCov().asEigen();
			worst = std::max(worst, dx.cwiseAbs().maxCoeff());
			worst = std::max(worst, dP.cwiseAbs().maxCoeff() /
			                            std::max(1e-300, P.asEigen().cwiseAbs().maxCoeff()));
		}
		// At least one landmark per true one; more where a correct pairing fails the 0.99 gate
		// (1 % of them), in MRPT's filter as in ours (same state size at every step above).
		EXPECT_GE(created, sc.landmarks.size()) << "seed " << seed;
		EXPECT_GT(associated, 100u);
		EXPECT_LT(worst, 1e-9) << "seed " << seed;
		// The landmarks started by -1 readings are named from kFirstResolvedId on.
		for (const auto& l : allStaticLandmarks(dyn)) EXPECT_GE(l.id, estimator::kFirstResolvedId);
	}
}

TEST(MrptConventions, UnknownIdsMinusOneAfterTheFirstSightingEqualsTheIdRun)
{
	// The default filter (Cartesian model): each landmark's first reading has its ID, the later
	// ones -1. Associated correctly, the run equals the run with every ID given. Noise-free
	// readings, so that no correct pairing fails the chi-square gate (1 % of them would).
	dynslam_test::TinyScenarioOptions o = scenario(3);
	o.noise = false;
	const auto sc = dynslam_test::makeTinyScenario(o);
	const auto frames = anonymous(sc, true);
	CDynamicKFSLAM2D withIds, withUnknown;
	size_t associated = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		withIds.processActionObservation(sc.actions[k], sc.frames[k]);
		ASSERT_NO_THROW(withUnknown.processActionObservation(sc.actions[k], frames[k]));
		EXPECT_EQ(withUnknown.getLastStepReport().unknown_id_new, 0u) << "step " << k;
		associated += withUnknown.getLastStepReport().unknown_id_associated;
	}
	EXPECT_GT(associated, 100u);
	const Eigen::VectorXd dx = withIds.fullMean().asEigen() - withUnknown.fullMean().asEigen();
	EXPECT_LT(dx.cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_EQ(allStaticLandmarks(withIds).size(), allStaticLandmarks(withUnknown).size());
}

TEST(MrptConventions, UnknownIdsOtherInvalidIdsAreStillRejectedWithAClearMessage)
{
	const auto sc = dynslam_test::makeTinyScenario(scenario(1));
	auto obs = std::make_shared<mrpt::obs::CObservationBearingRange>(
	    *sc.frames[0]->getObservationByClass<mrpt::obs::CObservationBearingRange>());
	obs->sensedData.at(0).landmarkID = 2147483647;
	auto sf = mrpt::obs::CSensoryFrame::Create();
	sf->insert(obs);
	CDynamicKFSLAM2D dyn;
	try
	{
		dyn.processActionObservation(sc.actions[0], sf);
		FAIL() << "no error";
	}
	catch (const std::runtime_error& e)
	{
		const std::string msg = e.what();
		EXPECT_NE(msg.find("landmark ID 2147483647"), std::string::npos) << msg;
		EXPECT_NE(msg.find("100000..999999999"), std::string::npos) << msg;
		EXPECT_EQ(msg.find(">= 100000"), std::string::npos) << msg;
	}
}

TEST(MrptConventions, AStepWithoutOdometryUsesStdsQNoOdoAsMrptDoes)
{
	// Issue 30, item 9: an action collection without a CActionRobotMovement2D threw. MRPT's
	// CRangeBearingKFSLAM2D takes u = 0 and Q = diag(stds_Q_no_odo^2) (0.10 m, 0.10 m, 4 deg):
	// ours, with MRPT's start and range-bearing model, must give the same mean and covariance.
	const auto sc = dynslam_test::makeTinyScenario(scenario(4));
	mrpt::slam::CRangeBearingKFSLAM2D rb;
	rb.options.std_sensor_range = 0.01f;
	rb.options.std_sensor_yaw = 0.001f;
	rb.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	CDynamicKFSLAM2D dyn;
	dyn.options.measurement_model = models::MeasurementModel::RangeBearing;
	const float sr = rb.options.std_sensor_range, sy = rb.options.std_sensor_yaw;
	dyn.options.Sigma_v = Eigen::Vector2d(double(sr * sr), double(sy * sy)).asDiagonal();
	dyn.options.Sigma_0.setZero();
	dyn.options.skip_prediction_on_empty_map = true;
	dyn.reset();
	double worst = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		auto a = (k == 10 || k == 20) ? mrpt::obs::CActionCollection::Create() : sc.actions[k];
		auto f = sc.frames[k];
		rb.processActionObservation(a, f);
		ASSERT_NO_THROW(dyn.processActionObservation(a, f)) << "step " << k;
		mrpt::poses::CPosePDFGaussian pose;
		std::vector<mrpt::math::TPoint2D> lms;
		std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
		mrpt::math::CVectorDouble x;
		mrpt::math::CMatrixDouble P;
		rb.getCurrentState(pose, lms, ids, x, P);
		ASSERT_EQ(size_t(x.size()), size_t(dyn.fullMean().size())) << "step " << k;
		worst = std::max(worst, (x.asEigen() - dyn.fullMean().asEigen()).cwiseAbs().maxCoeff());
		worst = std::max(worst, (P.asEigen() - dyn.fullCov().asEigen()).cwiseAbs().maxCoeff() /
		                            P.asEigen().cwiseAbs().maxCoeff());
	}
	EXPECT_LT(worst, 1e-9);
}
