// The outlier-handling update engines (robust_update_engines.h): equal to the plain sparse
// update without outliers, down-weighting/rejecting an injected outlier, bad parameters, and
// the gate with recovery that cannot lock out (the MRCLAM robot-4 case: a heading error larger
// than its covariance admits).
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/robust_update_engines.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <random>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
struct TScene
{
	Eigen::VectorXd x;  ///< prior estimate: ego + landmarks
	ekf::RowMatrixXd P;
	Eigen::VectorXd truth;
	std::vector<TStaticObservation> obs;
	TUpdateContext ctx;
};

/// Ego at (1, 2, 0.3) estimated with a small error, 6 landmarks around it, Cartesian readings
/// from the true state with noise N(0, 0.1^2) (seeded).
TScene scene(double headingError = 0.02, double egoVar = 0.01, unsigned seed = 3)
{
	TScene s;
	const int n = 6;
	s.truth.resize(3 + 2 * n);
	s.truth.head<3>() << 1, 2, 0.3;
	for (int i = 0; i < n; ++i)
		s.truth.segment<2>(3 + 2 * i) << 1 + 4 * std::cos(i), 2 + 4 * std::sin(i);
	s.x = s.truth;
	s.x.head<3>() += Eigen::Vector3d(0.05, -0.04, headingError);
	s.P = ekf::RowMatrixXd::Identity(3 + 2 * n, 3 + 2 * n) * 0.001;
	s.P.topLeftCorner<3, 3>() = egoVar * Eigen::Matrix3d::Identity();
	s.P(2, 2) = egoVar / 10;
	s.ctx.R = 0.01 * Eigen::Matrix2d::Identity();
	std::mt19937 rng(seed);
	std::normal_distribution<double> nz(0, 0.1);
	for (int i = 0; i < n; ++i)
	{
		const Eigen::Vector2d z =
		    models::observe(s.ctx.model, s.truth.head<3>(), s.truth.segment<2>(3 + 2 * i)) +
		    Eigen::Vector2d(nz(rng), nz(rng));
		s.obs.push_back({i, z, 3 + 2 * i});
	}
	return s;
}
}  // namespace

TEST(RobustEngines, WithoutOutliersHuberAndRecoveryEqualThePlainSparseUpdate)
{
	auto a = scene(), b = scene(), c = scene();
	CSparseUpdateEngine plain;
	CRobustUpdateEngine huber(RobustKernel::Huber, 3.0, 5);
	const auto ra = plain.update(a.x, a.P, a.obs, a.ctx);
	const auto rb = huber.update(b.x, b.P, b.obs, b.ctx);
	EXPECT_EQ(ra.updates, 6u);
	EXPECT_EQ(rb.updates, 6u);
	for (double w : huber.lastWeights()) EXPECT_EQ(w, 1.0);
	EXPECT_EQ(huber.lastIterations(), 1);
	EXPECT_LT((a.x - b.x).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_LT((a.P - b.P).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_NEAR(ra.nis, rb.nis, 1e-12);

	// The gate with recovery, nothing gated: the gated sparse update.
	auto d = scene();
	a = scene();
	a.ctx.gate_threshold = d.ctx.gate_threshold = gateThreshold2Dof(0.99);
	CGateRecoveryUpdateEngine rec({});
	const auto r1 = plain.update(a.x, a.P, a.obs, a.ctx);
	const auto r2 = rec.update(d.x, d.P, d.obs, d.ctx);
	EXPECT_EQ(r1.gated_out, 0u);
	EXPECT_EQ(r2.gated_out, 0u);
	EXPECT_LT((a.x - d.x).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_LT((a.P - d.P).cwiseAbs().maxCoeff(), 1e-12);

	// Cauchy weighs every reading below 1; with a huge c it tends to the plain update.
	CRobustUpdateEngine cauchy(RobustKernel::Cauchy, 1e6, 5);
	cauchy.update(c.x, c.P, c.obs, c.ctx);
	EXPECT_LT((a.x - c.x).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RobustEngines, AnInjectedOutlierIsDownWeightedOrRejected)
{
	const auto clean = [] { return scene(); };
	auto ref = clean();
	CSparseUpdateEngine plain;
	plain.update(ref.x, ref.P, ref.obs, ref.ctx);  // the update without the outlier
	const auto withOutlier = [&]
	{
		auto s = clean();
		s.obs[2].z += Eigen::Vector2d(2.0, -1.5);  // 25 sigma of R
		return s;
	};
	auto p = withOutlier();
	plain.update(p.x, p.P, p.obs, p.ctx);
	const double damage = (p.x - ref.x).head<3>().norm();
	EXPECT_GT(damage, 0.05);  // the plain update is dragged by it

	for (auto k : {RobustKernel::Huber, RobustKernel::Cauchy})
	{
		auto s = withOutlier();
		CRobustUpdateEngine e(k, 2.0, 10);
		e.update(s.x, s.P, s.obs, s.ctx);
		const auto& w = e.lastWeights();
		EXPECT_LT(w[2], 0.15) << e.name();
		for (size_t i = 0; i < w.size(); ++i)
		{
			if (i != 2)
			{
				EXPECT_GT(w[i], 0.5) << e.name() << " " << i;
			}
		}
		EXPECT_LT((s.x - ref.x).head<3>().norm(), 0.25 * damage) << e.name();
	}
	auto g = withOutlier();
	g.ctx.gate_threshold = gateThreshold2Dof(0.99);
	CGateRecoveryUpdateEngine rec({});
	const auto r = rec.update(g.x, g.P, g.obs, g.ctx);
	EXPECT_EQ(r.gated_out, 1u);
	EXPECT_EQ(r.updates, 5u);
	EXPECT_EQ(rec.inflations(), 0u);
}

TEST(RobustEngines, BadParametersAreClearErrors)
{
	EXPECT_THROW(CRobustUpdateEngine(RobustKernel::Huber, 0.0, 5), std::invalid_argument);
	EXPECT_THROW(CRobustUpdateEngine(RobustKernel::Cauchy, -1.0, 5), std::invalid_argument);
	EXPECT_THROW(CRobustUpdateEngine(RobustKernel::Huber, std::nan(""), 5), std::invalid_argument);
	EXPECT_THROW(CRobustUpdateEngine(RobustKernel::Huber, 1.0, 0), std::invalid_argument);
	TGateRecoveryParams p;
	p.count = 0;
	EXPECT_THROW(CGateRecoveryUpdateEngine{p}, std::invalid_argument);
	p = {};
	p.inflation = 1.0;
	EXPECT_THROW(CGateRecoveryUpdateEngine{p}, std::invalid_argument);
	p = {};
	p.min_updates = -1;
	EXPECT_THROW(CGateRecoveryUpdateEngine{p}, std::invalid_argument);
	auto s = scene();
	CGateRecoveryUpdateEngine rec({});
	EXPECT_THROW(rec.update(s.x, s.P, s.obs, s.ctx), std::invalid_argument);  // no gate
	// An empty step: no update, state unchanged.
	CRobustUpdateEngine huber(RobustKernel::Huber, 1.0, 3);
	const Eigen::VectorXd x0 = s.x;
	const auto r = huber.update(s.x, s.P, {}, s.ctx);
	EXPECT_EQ(r.updates, 0u);
	EXPECT_EQ(s.x, x0);
}

TEST(RobustEngines, GateWithRecoveryCannotLockOut)
{
	// Heading 0.3 rad off with a 1e-3 rad standard deviation: every reading fails the gate.
	const int count = 3;
	const auto run = [&](IUpdateEngine& e, int steps, int* firstAdmitted)
	{
		auto s = scene(0.3, 1e-6);
		s.ctx.gate_threshold = gateThreshold2Dof(0.99);
		*firstAdmitted = -1;
		for (int k = 0; k < steps; ++k)
		{
			s.P.topLeftCorner<3, 3>() += 1e-8 * Eigen::Matrix3d::Identity();  // process noise
			const auto r = e.update(s.x, s.P, s.obs, s.ctx);
			if (r.updates > 0 && *firstAdmitted < 0) *firstAdmitted = k;
		}
		return std::abs(models::wrapToPi(s.x[2] - s.truth[2]));
	};
	int first = 0;
	CSparseUpdateEngine plain;
	EXPECT_NEAR(run(plain, 30, &first), 0.3, 1e-6);  // locked out for ever
	EXPECT_EQ(first, -1);

	TGateRecoveryParams p;
	p.count = count;
	p.inflation = 10;
	p.min_updates = 0;
	CGateRecoveryUpdateEngine rec(p);
	const double err = run(rec, 30, &first);
	EXPECT_GE(first, count - 1);  // not before count rejections
	EXPECT_LE(first, count + 6);  // 0.3 rad / 1e-3 rad needs ~(300/3)^2 = 1e4 = 10^4 inflation
	EXPECT_LT(err, 0.03);
	EXPECT_GT(rec.inflations(), 0u);

	// Landmarks never accepted are not "well established": min_updates > 0 never triggers here.
	p.min_updates = 1;
	CGateRecoveryUpdateEngine strict(p);
	EXPECT_NEAR(run(strict, 30, &first), 0.3, 1e-6);
	EXPECT_EQ(strict.inflations(), 0u);
}

TEST(RobustEngines, OneIniKeySelectsTheEngineAndBadValuesAreClearErrors)
{
	const std::string base =
	    "[DynamicKFSLAM]\n"
	    "measurement_model = cartesian\n"
	    "Sigma_v = [1e-4 1e-4]\n"
	    "Sigma_xi = [0.1 0.1]\n";
	const auto engineOf = [&](const std::string& extra)
	{
		mrpt::config::CConfigFileMemory ini(base + extra);
		CDynamicKFSLAM2D kf;
		kf.loadOptions(ini, "DynamicKFSLAM");
		return kf.updateEngine().name();
	};
	EXPECT_EQ(engineOf(""), "sparse");  // default: gate (with innovation_gate = 0, no gate)
	EXPECT_EQ(engineOf("outlier_method = none\n"), "sparse");
	EXPECT_EQ(engineOf("outlier_method = huber\n"), "huber");
	EXPECT_EQ(engineOf("outlier_method = Cauchy\nrobust_kernel_c = 3\n"), "cauchy");
	EXPECT_EQ(engineOf("outlier_method = gate_recovery\ninnovation_gate = 0.999\n"),
	          "gate_recovery");
	for (const char* bad :
	     {"outlier_method = jcbb\n",  // no confidence: innovation_gate = 0 (test_jcbb.cpp)
	      "outlier_method = huber\nrobust_kernel_c = 0\n",
	      "outlier_method = cauchy\nrobust_kernel_c = -2\n", "robust_iterations = 0\n",
	      "outlier_method = gate_recovery\n",  // no gate to recover from
	      "outlier_method = gate_recovery\ninnovation_gate = 0.99\nrecovery_count = 0\n",
	      "recovery_inflation = 1\n", "recovery_min_updates = -1\n",
	      "outlier_method = huber\nstatic_update = mrpt\n"})
		EXPECT_THROW(engineOf(bad), std::exception) << bad;
}
