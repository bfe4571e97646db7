/** With no moving objects the dynamic filter reproduces MRPT's CRangeBearingKFSLAM2D on the
 * same action/observation sequence: ego pose, landmarks and the full covariance; also with a
 * sensor that is not at the robot's origin (sensorLocationOnRobot). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <iostream>

#include "tiny_scenario.h"

using namespace dynslam;

namespace
{
dynslam_test::TinyScenarioOptions options(unsigned seed)
{
	dynslam_test::TinyScenarioOptions o;
	o.steps = 40;
	o.landmarks = 15;
	o.seed = seed;
	return o;
}

void runBoth(mrpt::bayes::TKFMethod method, const dynslam_test::TinyScenarioOptions& o,
             double* worstX, double* worstP, bool sparse = false)
{
	const auto sc = dynslam_test::makeTinyScenario(o);

	mrpt::slam::CRangeBearingKFSLAM2D rb;
	rb.options.std_sensor_range = float(std::sqrt(o.Sigma_rb(0, 0)));
	rb.options.std_sensor_yaw = float(std::sqrt(o.Sigma_rb(1, 1)));
	rb.KF_options.method = method;
	rb.setMinLoggingLevel(mrpt::system::LVL_ERROR);

	CDynamicKFSLAM2D dyn;
	dyn.options.measurement_model = models::MeasurementModel::RangeBearing;
	// MRPT's R: squares of float stds, computed in float.
	const float sr = rb.options.std_sensor_range, sy = rb.options.std_sensor_yaw;
	const float sr2 = sr * sr, sy2 = sy * sy;
	dyn.options.Sigma_v = Eigen::Vector2d(double(sr2), double(sy2)).asDiagonal();
	dyn.options.Sigma_0.setZero();
	dyn.options.skip_prediction_on_empty_map = true;
	dyn.KF_options.method = method;
	dyn.options.sparse_static_update = sparse;
	dyn.reset();

	*worstX = *worstP = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		auto a = sc.actions[k];
		auto f = sc.frames[k];
		rb.processActionObservation(a, f);
		dyn.processActionObservation(a, f);

		mrpt::poses::CPosePDFGaussian pose;
		std::vector<mrpt::math::TPoint2D> lms;
		std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
		mrpt::math::CVectorDouble x;
		mrpt::math::CMatrixDouble P;
		rb.getCurrentState(pose, lms, ids, x, P);
		ASSERT_EQ(size_t(x.size()), size_t(dyn.fullMean().size())) << "step " << k;
		const Eigen::VectorXd dx = x.asEigen() - dyn.fullMean().asEigen();
		const Eigen::MatrixXd dP = P.asEigen() - dyn.fullCov().asEigen();
		*worstX = std::max(
		    *worstX, dx.cwiseAbs().maxCoeff() / std::max(1.0, x.asEigen().cwiseAbs().maxCoeff()));
		*worstP = std::max(*worstP, dP.cwiseAbs().maxCoeff() /
		                                std::max(1e-300, P.asEigen().cwiseAbs().maxCoeff()));
		// Same landmark IDs in the same slots.
		for (const auto& [slot, id] : ids) EXPECT_EQ(dyn.getSlots().at(slot).id, id);
	}
}
}  // namespace

TEST(DynamicVsMrpt, ReproducesRangeBearingKFSLAM2D_Naive)
{
	for (unsigned seed : {1u, 2u, 3u})
	{
		double ex, ep;
		runBoth(mrpt::bayes::kfEKFNaive, options(seed), &ex, &ep);
		std::cout << "seed " << seed << ": worst relative |dx| " << ex << ", |dP| " << ep << "\n";
		EXPECT_LT(ex, 1e-9) << "seed " << seed;
		EXPECT_LT(ep, 1e-9) << "seed " << seed;
	}
}

TEST(DynamicVsMrpt, ReproducesRangeBearingKFSLAM2D_SparseUpdate)
{
	double ex, ep;
	runBoth(mrpt::bayes::kfEKFNaive, options(5), &ex, &ep, true);
	std::cout << "sparse update vs MRPT: worst relative |dx| " << ex << ", |dP| " << ep << "\n";
	EXPECT_LT(ex, 1e-9);
	EXPECT_LT(ep, 1e-9);
}

TEST(DynamicVsMrpt, ReproducesRangeBearingKFSLAM2D_Davison)
{
	double ex, ep;
	runBoth(mrpt::bayes::kfEKFAlaDavison, options(4), &ex, &ep);
	EXPECT_LT(ex, 1e-9);
	EXPECT_LT(ep, 1e-9);
}

TEST(DynamicVsMrpt, UnevenCorrelatedOdometryNoiseAtNonZeroHeading)
{
	// The action covariance is on the robot-frame increment; both filters rotate it into the
	// state (Q = J S J^T). Uneven along/across variances with cross terms, and a heading that
	// turns 0.3 rad per step (across +-pi), so that Q = S would differ from J S J^T.
	for (bool sparse : {false, true})
	{
		dynslam_test::TinyScenarioOptions o = options(6);
		o.u = Eigen::Vector3d(0.5, 0.05, 0.3);
		o.Sigma_w << 4e-4, 1.5e-4, 2e-5, 1.5e-4, 1e-4, -1e-5, 2e-5, -1e-5, 1e-5;
		double ex, ep;
		runBoth(mrpt::bayes::kfEKFNaive, o, &ex, &ep, sparse);
		std::cout << "uneven correlated odometry noise (sparse " << sparse
		          << "): worst relative |dx| " << ex << ", |dP| " << ep << "\n";
		EXPECT_LT(ex, 1e-9);
		EXPECT_LT(ep, 1e-9);
	}
}

TEST(DynamicVsMrpt, SparseStaticUpdateEqualsMrptUpdate)
{
	// With objects, both measurement models: the sparse path equals MRPT's kfEKFNaive update.
	for (bool cart : {true, false})
	{
		dynslam_test::TinyScenarioOptions o;
		o.objects = 2;
		o.steps = 40;
		o.landmarks = 20;
		o.cartesian_noise = cart;
		const auto sc = dynslam_test::makeTinyScenario(o);
		CDynamicKFSLAM2D a, b;
		for (CDynamicKFSLAM2D* f : {&a, &b})
		{
			f->options.measurement_model =
			    cart ? models::MeasurementModel::Cartesian : models::MeasurementModel::RangeBearing;
			f->options.Sigma_v = cart ? o.Sigma_v : o.Sigma_rb;
			f->options.Sigma_0 = o.Sigma_w;
			f->KF_options.method = mrpt::bayes::kfEKFNaive;
		}
		a.options.sparse_static_update = false;
		b.options.sparse_static_update = true;
		a.reset();
		b.reset();
		double worst = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			a.processActionObservation(sc.actions[k], sc.frames[k]);
			b.processActionObservation(sc.actions[k], sc.frames[k]);
			ASSERT_EQ(a.fullMean().size(), b.fullMean().size());
			const Eigen::MatrixXd Pa = a.fullCov().asEigen(), Pb = b.fullCov().asEigen();
			worst = std::max(worst, (Pa - Pb).cwiseAbs().maxCoeff() / Pa.cwiseAbs().maxCoeff());
			worst = std::max(
			    worst, (a.fullMean().asEigen() - b.fullMean().asEigen()).cwiseAbs().maxCoeff() /
			               std::max(1.0, a.fullMean().asEigen().cwiseAbs().maxCoeff()));
			EXPECT_NEAR(a.getLastStepReport().nis_static, b.getLastStepReport().nis_static,
			            1e-7 * std::max(1.0, a.getLastStepReport().nis_static));
		}
		std::cout << (cart ? "cartesian" : "range-bearing") << ": sparse vs MRPT worst relative "
		          << worst << "\n";
		EXPECT_LT(worst, 1e-9);
	}
}

TEST(DynamicVsMrpt, SensorNotAtTheRobotsOrigin)
{
	// The readings are taken from x (+) s, s = (0.3 m, -0.1 m, 0.2 rad), and the observations
	// carry s in sensorLocationOnRobot (with a height of 0.5 m, which both filters ignore:
	// MRPT uses CPose2D(sensorLocationOnRobot), i.e. x, y and yaw). Both update engines and
	// MRPT's two update methods.
	struct TCase
	{
		mrpt::bayes::TKFMethod method;
		bool sparse;
		unsigned seed;
	};
	for (const TCase& c :
	     {TCase{mrpt::bayes::kfEKFNaive, false, 1}, TCase{mrpt::bayes::kfEKFNaive, true, 2},
	      TCase{mrpt::bayes::kfEKFAlaDavison, false, 3}})
	{
		dynslam_test::TinyScenarioOptions o = options(c.seed);
		o.sensor = Eigen::Vector3d(0.3, -0.1, 0.2);
		o.sensor_z = 0.5;
		double ex, ep;
		runBoth(c.method, o, &ex, &ep, c.sparse);
		std::cout << "sensor offset (method " << int(c.method) << ", sparse " << c.sparse
		          << "): worst relative |dx| " << ex << ", |dP| " << ep << "\n";
		EXPECT_LT(ex, 1e-9);
		EXPECT_LT(ep, 1e-9);
	}
}
