/** The CTRV transition (models::ctrvPredict, issue 13): its Jacobian vs central differences at
 * seeded random states, at the +-pi wrap of the object rotation and at turn rates 0, +-1e-9,
 * across the series threshold |omega dt| = 1e-2 and far from it; the omega -> 0 limit is the CV
 * step; a full circle comes back to its start; zero speed stays put. */
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam::models;
using core_test::checkJacobian;
using core_test::VecFn;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
/** Turn rates [rad/s] for dt: random, zero, tiny, both sides of the series threshold. */
std::vector<double> turnRates(double dt)
{
	std::vector<double> w{0.0, 1e-9, -1e-9, 1e-5};
	for (const double a : {1e-2, -1e-2})
		for (const double e : {-1e-7, 0.0, 1e-7}) w.push_back((a + e) / dt);
	for (int i = 0; i < 20; ++i) w.push_back(uniform(-1.5, 1.5));
	return w;
}
}  // namespace

TEST(ObjectMotionJacobians, CtrvPrediction)
{
	dynslam_test::rng(1302);
	double worst = 0;
	std::vector<double> headings = core_test::wrapHeadings();
	for (int i = 0; i < 5; ++i) headings.push_back(uniform(-M_PI, M_PI));
	for (const double th : headings)
	{
		const double dt = uniform(0.05, 1.0);
		for (const double w : turnRates(dt))
		{
			VectorXd s = core_test::randomVector(6, -10, 10);
			s[2] = th;
			s[5] = w;
			MatrixXd J;
			const VectorXd out = ctrvPredict(s, dt, &J);
			EXPECT_LE(std::abs(out[2]), M_PI);
			const VecFn f = [&](const VectorXd& v) { return ctrvPredict(v, dt); };
			EXPECT_TRUE(checkJacobian(J, f, s, {2}, worst)) << "omega " << w << " dt " << dt;
			// Speed and turn rate are kept; the heading turns by omega dt.
			EXPECT_NEAR(out.segment<2>(3).norm(), s.segment<2>(3).norm(), 1e-12);
			EXPECT_EQ(out[5], w);
			EXPECT_NEAR(wrapToPi(out[2] - th - w * dt), 0, 1e-12);
		}
	}
	core_test::reportWorst("ctrvPredict", worst);
}

TEST(ObjectMotionCtrv, ZeroTurnRateIsTheCvStep)
{
	dynslam_test::rng(1303);
	for (int i = 0; i < 20; ++i)
	{
		VectorXd s = core_test::randomVector(6, -10, 10);
		s[2] = uniform(-M_PI, M_PI);
		s[5] = 0;
		MatrixXd Jc, Jv;
		const VectorXd a = ctrvPredict(s, 0.5, &Jc), b = cvPredict(s, 0.5, &Jv);
		EXPECT_LT((a - b).norm(), 1e-14);
		// The turn-rate column differs (the velocity turns); the others are CV's.
		EXPECT_LT((Jc.leftCols(5) - Jv.leftCols(5)).norm(), 1e-14);
		// Continuity of the series at the threshold |omega dt| = 1e-2.
		s[5] = 1e-2 / 0.5;
		const VectorXd lo =
		    ctrvPredict((VectorXd(s) << s.head(5), s[5] * (1 - 1e-12)).finished(), 0.5);
		const VectorXd hi = ctrvPredict(s, 0.5);
		EXPECT_LT((lo - hi).norm(), 1e-11);
	}
	// A translation-only pose has no turn rate: CTRV is CV.
	const VectorXd s4 = (VectorXd(4) << 1, 2, 3, 4).finished();
	EXPECT_EQ(ctrvPredict(s4, 0.3), cvPredict(s4, 0.3));
}

TEST(ObjectMotionCtrv, FullCircleAndZeroSpeed)
{
	// n steps of omega = 2 pi / (n dt): the reference point is back where it started, on a
	// circle of radius |v| / omega (the CV step would be n dt |v| away).
	const int n = 40;
	const double dt = 0.25, w = 2 * M_PI / (n * dt);
	VectorXd s(6);
	s << 3, -1, 0.2, 2.0, 0.5, w;
	const VectorXd s0 = s;
	double farthest = 0;
	for (int i = 0; i < n; ++i)
	{
		s = ctrvPredict(s, dt);
		farthest = std::max(farthest, (s.head<2>() - s0.head<2>()).norm());
	}
	EXPECT_LT((s.head<2>() - s0.head<2>()).norm(), 1e-12);
	EXPECT_LT((s.segment<2>(3) - s0.segment<2>(3)).norm(), 1e-12);
	EXPECT_NEAR(wrapToPi(s[2] - s0[2]), 0, 1e-12);
	EXPECT_NEAR(farthest, 2 * s0.segment<2>(3).norm() / w, 1e-2);  // the diameter (sampled)
	// Zero speed (the documented CTRV corner case: nothing divides by the speed): only the
	// rotation changes; the Jacobian stays finite.
	VectorXd z(6);
	z << 1, 2, 0.3, 0, 0, 0.7;
	MatrixXd J;
	const VectorXd out = ctrvPredict(z, dt, &J);
	EXPECT_EQ(out.head<2>(), z.head<2>());
	EXPECT_TRUE(J.allFinite());
	EXPECT_THROW(ctrvPredict(VectorXd::Zero(5), dt), std::invalid_argument);
}
