/** object_model = ca (constant acceleration, estimator/constant_acceleration.h): the transition
 * Jacobian J_out_s and the initial velocity's J_v_xi against central differences (3-dof and
 * translation-only poses, rotations next to +-pi), the white-jerk process noise against the
 * integral that defines it, the zero-acceleration limit (the cv step), the EKF's whole-state
 * gauge term for the 6-entry velocity block, and the options and bad input (keys named). */
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/constant_acceleration.h>
#include <dynslam/estimator/seam_registries.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "model_test_utils.h"
#include "object_model_setup.h"
#include "tiny_scenario.h"

using namespace dynslam;
using dynslam_test::errorOf;
using dynslam_test::numericJ;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using estimator::caPredict;
using estimator::caProcessNoise;
using estimator::CConstantAcceleration;
using estimator::TCvParams;

namespace
{
double relErr(const MatrixXd& A, const MatrixXd& B)
{
	return (A - B).cwiseAbs().maxCoeff() / std::max(1.0, B.cwiseAbs().maxCoeff());
}

TCvParams params(double dt)
{
	TCvParams p;
	p.dt = dt;
	p.jerk_psd = Eigen::Vector3d(0.02, 0.03, 0.004);
	p.accel_prior_std = Eigen::Vector3d(0.4, 0.6, 0.05);
	return p;
}
}  // namespace

TEST(ObjectMotionJacobians, CaPrediction)
{
	std::mt19937 g(3201);
	std::uniform_real_distribution<double> U(-5, 5), T(0.05, 1.0);
	double worst = 0;
	for (const double th : {0.3, M_PI - 1e-7, -M_PI + 1e-7, -2.0, 3.1})
		for (int d : {3, 2})
		{
			const double dt = T(g);
			const CConstantAcceleration m(params(dt));
			VectorXd s(3 * d);
			for (Eigen::Index i = 0; i < s.size(); ++i) s[i] = U(g);
			if (d == 3) s[2] = th;
			MatrixXd J, Q;
			const VectorXd out = m.predict(s, &J, &Q);
			ASSERT_EQ(J.rows(), 3 * d);
			ASSERT_EQ(J.cols(), 3 * d);
			const std::vector<int> angles = d == 3 ? std::vector<int>{2} : std::vector<int>{};
			const MatrixXd Jn =
			    numericJ([&](const VectorXd& x) { return caPredict(x, dt); }, s, angles);
			const double e = relErr(J, Jn);
			EXPECT_LT(e, 1e-8) << "d " << d << " theta " << th << "\n" << J << "\n\n" << Jn;
			worst = std::max(worst, e);
			if (d == 3)
			{
				EXPECT_LE(std::abs(out[2]), M_PI);
			}
			// The acceleration is kept; the velocity gains dt a.
			EXPECT_EQ(out.tail(d), s.tail(d));
			EXPECT_LT((out.segment(d, d) - s.segment(d, d) - dt * s.tail(d)).cwiseAbs().maxCoeff(),
			          1e-12);
		}
	std::printf("[ measured ] caPredict: worst relative Jacobian error %.2e\n", worst);
}

TEST(ObjectMotionJacobians, CaInitialVelocity)
{
	std::mt19937 g(3202);
	std::uniform_real_distribution<double> U(-5, 5);
	for (int d : {3, 2})
		for (int steps : {1, 2, 5})
		{
			const CConstantAcceleration m(params(0.4));
			VectorXd xi(d);
			for (Eigen::Index i = 0; i < d; ++i) xi[i] = U(g);
			MatrixXd J, Sigma;
			const VectorXd v = m.initialVelocity(xi, steps, &J, &Sigma);
			ASSERT_EQ(v.size(), 2 * d);
			ASSERT_EQ(J.rows(), 2 * d);
			ASSERT_EQ(J.cols(), d);
			const MatrixXd Jn = numericJ([&](const VectorXd& x)
			                             { return m.initialVelocity(x, steps, nullptr, nullptr); },
			                             xi, {});
			EXPECT_LT(relErr(J, Jn), 1e-8) << "d " << d << " steps " << steps;
			// v = xi / e (cv's), a = 0; the prior couples v and a by e/2 (constant_acceleration.h).
			const double e = steps * 0.4;
			EXPECT_LT((v.head(d) - models::cvInitialVelocity(xi, e)).cwiseAbs().maxCoeff(), 1e-15);
			EXPECT_TRUE(v.tail(d).isZero(0));
			const MatrixXd Sa =
			    params(0.4).accel_prior_std.head(d).array().square().matrix().asDiagonal();
			const MatrixXd Sv =
			    TCvParams().velocity_prior_std.head(d).array().square().matrix().asDiagonal();
			EXPECT_LT(relErr(Sigma.bottomRightCorner(d, d), Sa), 1e-15);
			EXPECT_LT(relErr(Sigma.topRightCorner(d, d), 0.5 * e * Sa), 1e-15);
			EXPECT_LT(relErr(Sigma.topLeftCorner(d, d), Sv + 0.25 * e * e * Sa), 1e-15);
			EXPECT_EQ(Sigma, Sigma.transpose());
			EXPECT_GT(Sigma.llt().matrixL().toDenseMatrix().diagonal().minCoeff(), 0);
		}
	const CConstantAcceleration m(params(0.4));
	EXPECT_THROW(m.initialVelocity(Eigen::Vector3d::Zero(), 0, nullptr, nullptr),
	             std::invalid_argument);  // an object seen once has no velocity
}

TEST(ObjectModelCa, ProcessNoiseIsTheIntegralOfWhiteJerk)
{
	// Q = int_0^dt Phi(t) G q G^T Phi(t)^T dt, Phi(t) = [1 t t^2/2; 0 1 t; 0 0 1], G = [0 0 1]^T,
	// per axis: Simpson's rule with 2000 intervals (exact to rounding: the integrand is a
	// polynomial of degree 4).
	const double dt = 0.7;
	const Eigen::Vector3d q(0.02, 0.5, 3e-3);
	const MatrixXd Q = caProcessNoise(q, dt);
	ASSERT_EQ(Q.rows(), 9);
	const int n = 2000;
	for (int i = 0; i < 3; ++i)
	{
		Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
		for (int k = 0; k <= n; ++k)
		{
			const double t = dt * k / n, w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
			const Eigen::Vector3d c(t * t / 2, t, 1);  // Phi(t) G
			I += w * q[i] * c * c.transpose();
		}
		I *= dt / (3.0 * n);
		Eigen::Matrix3d Qi;
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) Qi(r, c) = Q(3 * r + i, 3 * c + i);
		EXPECT_LT(relErr(Qi, I) / std::max(1e-300, I.cwiseAbs().maxCoeff()), 1e-12)
		    << "axis " << i << "\n"
		    << Qi << "\n\n"
		    << I;
		EXPECT_GT(Qi.determinant(), 0) << "axis " << i;
	}
	// No coupling between axes.
	for (int r = 0; r < 9; ++r)
		for (int c = 0; c < 9; ++c)
			if (r % 3 != c % 3)
			{
				EXPECT_EQ(Q(r, c), 0.0) << r << "," << c;
			}
	// A translation-only pose: the first two axes.
	const MatrixXd Q2 = caProcessNoise(q.head(2), dt);
	EXPECT_EQ(Q2.rows(), 6);
	EXPECT_EQ(Q2(0, 0), Q(0, 0));
	EXPECT_EQ(Q2(3, 5), Q(4, 7));
}

TEST(ObjectModelCa, ZeroAccelerationIsTheCvStep)
{
	VectorXd s(9);
	s << 1.0, -2.0, M_PI - 0.01, 3.0, 0.5, 0.1, 0, 0, 0;
	MatrixXd J;
	const VectorXd ca = caPredict(s, 0.5, &J);
	const VectorXd cv = models::cvPredict(s.head(6), 0.5);
	EXPECT_LT((ca.head(6) - cv).cwiseAbs().maxCoeff(), 1e-15);
	EXPECT_THROW(caPredict(VectorXd::Zero(6 + 1), 0.5), std::invalid_argument);
	EXPECT_THROW(caPredict(VectorXd::Zero(4), 0.5), std::invalid_argument);
}

TEST(ObjectModelCa, RegistryMakesItWithAVelocityAndAccelerationBlock)
{
	const auto& r = estimator::objectMotionModels();
	estimator::TObjectMotionParams p;
	const auto m = r.make("ca", p);
	EXPECT_EQ(m->name(), "ca");
	EXPECT_TRUE(r.caps("ca").object_centric);
	EXPECT_TRUE(m->objectCentric());
	EXPECT_EQ(m->velocityDim(3), 6);
	EXPECT_EQ(m->velocityDim(2), 4);
	EXPECT_EQ(std::string(r.caps("ca").noise_key), "ca_jerk_psd");
}

TEST(ObjectModelCa, OptionsAndBadInput)
{
	const auto load = [](const std::string& extra)
	{ return dynslam_test::loadCartesianFilter(extra)->objectMotionModel().name(); };
	const std::string ca = "object_model = ca\n[ObjectModel]\ncv_dt = 0.5\n";
	EXPECT_EQ(load(ca), "ca");
	// Missing cv_dt: the error names it.
	EXPECT_NE(errorOf([&] { load("object_model = ca\n"); }).find("cv_dt"), std::string::npos);
	// Negative / non-finite spectral densities, non-positive prior stds, wrong lengths.
	for (const char* bad : {"[0.1 -1 0.1]", "[-1e-9 0 0]", "[0.1 0.1]", "[0.1 0.1 0.1 0.1]"})
	{
		const std::string e =
		    errorOf([&] { load(ca + "[ObjectModel]\nca_jerk_psd = " + bad + "\n"); });
		EXPECT_NE(e.find("ca_jerk_psd"), std::string::npos) << bad << ": '" << e << "'";
	}
	EXPECT_EQ(load(ca + "[ObjectModel]\nca_jerk_psd = [0 0 0]\n"),
	          "ca");  // the EKF accepts 0 (no noise)
	for (const char* bad : {"[0.5 0 0.1]", "[0.5 -1 0.1]", "[1 1]"})
	{
		const std::string e =
		    errorOf([&] { load(ca + "[ObjectModel]\nca_accel_prior_std = " + bad + "\n"); });
		EXPECT_NE(e.find("ca_accel_prior_std"), std::string::npos) << bad << ": '" << e << "'";
	}
	TCvParams p;
	p.jerk_psd[0] = std::nan("");
	EXPECT_NE(errorOf([&] { CConstantAcceleration m(p); }).find("ca_jerk_psd"), std::string::npos);
	p = TCvParams();
	p.accel_prior_std[2] = std::numeric_limits<double>::infinity();
	EXPECT_NE(errorOf([&] { CConstantAcceleration m(p); }).find("ca_accel_prior_std"),
	          std::string::npos);
	// The cv keys still apply (the velocity prior, the smoothing conflict).
	EXPECT_NE(errorOf([&] { load(ca + "[ObjectModel]\ncv_velocity_prior_std = [1 0 1]\n"); })
	              .find("cv_velocity_prior_std"),
	          std::string::npos);
	EXPECT_THROW(load("smoothing = true\nkeep_last_poses = 3\n" + ca), std::invalid_argument);
	// Read and dumped.
	const auto f = dynslam_test::loadCartesianFilter(
	    ca + "[ObjectModel]\nca_jerk_psd = [0.2 0.3 0.004]\nca_accel_prior_std = [1 2 0.3]\n");
	EXPECT_EQ(f->options.cv.jerk_psd, Eigen::Vector3d(0.2, 0.3, 0.004));
	EXPECT_EQ(f->options.cv.accel_prior_std, Eigen::Vector3d(1, 2, 0.3));
	std::ostringstream dump;
	f->options.dumpToTextStream(dump);
	EXPECT_NE(dump.str().find("ca_jerk_psd                    = [0.2 0.3 0.004]"),
	          std::string::npos)
	    << dump.str();
	EXPECT_NE(dump.str().find("ca_accel_prior_std             = [1 2 0.3]"), std::string::npos);
}

namespace
{
/** The tiny scenario's two objects through the EKF with `model`; prior_gauge = anchor. */
std::unique_ptr<CDynamicKFSLAM2D> runTiny(const std::string& model, size_t& updates)
{
	dynslam_test::TinyScenarioOptions o;
	o.objects = 2;
	o.features_per_object = 3;
	o.cartesian_noise = true;
	o.steps = 20;
	const auto sc = dynslam_test::makeTinyScenario(o);
	auto f = std::make_unique<CDynamicKFSLAM2D>();
	dynslam_test::configureObjectModel(*f, o, model);
	f->options.prior_gauge_anchor = true;
	f->options.Sigma_0 = Eigen::Vector3d(1e-2, 2e-2, 1e-3).asDiagonal();
	f->reset();
	updates = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		f->processActionObservation(sc.actions[k], sc.frames[k]);
		updates += f->getLastStepReport().object_feature_updates;
	}
	return f;
}

/** Track poses with a velocity; checks that each velocity has the pose's size. */
size_t velocitiesOf(const CDynamicKFSLAM2D& f)
{
	size_t n = 0;
	for (const auto& [obj, tr] : f.getObjectTracks())
		for (const auto& p : tr.poses)
			if (p.velocity.size() > 0)
			{
				EXPECT_EQ(p.velocity.size(), p.mean.size());
				EXPECT_EQ(p.velocity_cov.rows(), p.mean.size());
				++n;
			}
	return n;
}
}  // namespace

TEST(ObjectModelCa, RunsInTheEkfWithSixEntryVelocityBlocks)
{
	// The tiny scenario's objects with ca: every object gets a 6-entry velocity block (3 slots,
	// no pad), its readings update the state, the tracks report the velocity (3 entries) at the
	// same poses as cv, and with prior_gauge = anchor the whole-state gauge term covers the
	// block (the acceleration rotates like the velocity).
	size_t updates = 0, cvUpdates = 0;
	const auto f = runTiny("ca", updates);
	const auto cv = runTiny("cv", cvUpdates);
	EXPECT_GT(updates, 20u);
	EXPECT_EQ(updates, cvUpdates);  // no reading gated (no gate): the same readings used
	int blocks = 0;
	for (size_t b = 0; b < f->getLayout().size(); ++b)
		if (f->getLayout()[b].kind == estimator::BlockKind::ObjectVelocity)
		{
			EXPECT_EQ(f->getLayout()[b].dim, 6);
			EXPECT_EQ(f->getLayout()[b].slots(), 3);
			++blocks;
		}
	EXPECT_EQ(blocks, 2);
	const size_t withVelocity = velocitiesOf(*f);
	EXPECT_GT(withVelocity, 0u);
	EXPECT_EQ(withVelocity, velocitiesOf(*cv));
	// The whole state with the gauge term N Sigma_0 N^T: the acceleration rows of N are those of
	// a velocity (d/dtheta R a = [-ay; ax]).
	Eigen::VectorXd x;
	Eigen::MatrixXd P, P0;
	std::vector<std::string> labels;
	f->getStateWithoutPads(x, P, &labels);
	f->options.prior_gauge_anchor = false;
	f->getStateWithoutPads(x, P0, &labels);
	const Eigen::MatrixXd G = P - P0;
	int checked = 0;
	for (size_t i = 0; i < labels.size(); ++i)
	{
		const auto at = labels[i].rfind('.');
		if (labels[i].find(".v") == std::string::npos || labels[i].substr(at) != ".3") continue;
		const Eigen::Index a = Eigen::Index(i);  // ax; ay at a + 1; vx at a - 3, vy at a - 2
		for (const auto& [r, other] : {std::pair{a, a + 1}, std::pair{a - 3, a - 2}})
			EXPECT_NEAR(G(r, r), 1e-3 * x[other] * x[other], 1e-12 * (1 + x[other] * x[other]))
			    << labels[size_t(r)];
		EXPECT_NEAR(G(a + 1, a + 1), 1e-3 * x[a] * x[a], 1e-12 * (1 + x[a] * x[a]));
		EXPECT_NEAR(G(a + 2, a + 2), 0.0, 1e-15);  // alpha: unchanged
		EXPECT_GT(std::abs(x[a]) + std::abs(x[a + 1]), 0.0);
		++checked;
	}
	EXPECT_EQ(checked, 2);
}
