// outlier_method = jcbb (CJcbbUpdateEngine): equal to the gated update on a jointly compatible
// step, rejects a gross outlier as the gate does, and rejects readings that pass the gate one
// by one but not jointly (where MRPT's JCBB alone associates them); empty step, bad
// confidence, the INI key, and a whole EKF run.
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/ekf/CJcbbUpdateEngine.h>
#include <dynslam/eval/chi2.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "tiny_scenario.h"

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
struct TScene
{
	Eigen::VectorXd x;  ///< prior estimate: ego + landmarks
	ekf::RowMatrixXd P;
	std::vector<TStaticObservation> obs;
	TUpdateContext ctx;
};

/// Ego at (1, 2, 0.3) estimated with a small error, 6 landmarks around it, readings from the
/// true state with noise N(0, R) (seeded), Cartesian or range-bearing.
TScene randomScene(models::MeasurementModel m, unsigned seed = 3)
{
	TScene s;
	const int n = 6;
	Eigen::VectorXd truth(3 + 2 * n);
	truth.head<3>() << 1, 2, 0.3;
	for (int i = 0; i < n; ++i)
		truth.segment<2>(3 + 2 * i) << 1 + 4 * std::cos(i), 2 + 4 * std::sin(i);
	s.x = truth;
	s.x.head<3>() += Eigen::Vector3d(0.05, -0.04, 0.02);
	s.P = ekf::RowMatrixXd::Identity(3 + 2 * n, 3 + 2 * n) * 0.001;
	s.P.topLeftCorner<3, 3>() = Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal();
	s.ctx.model = m;
	const Eigen::Vector2d sd = m == models::MeasurementModel::Cartesian
	                               ? Eigen::Vector2d(0.1, 0.1)
	                               : Eigen::Vector2d(0.1, 0.02);
	s.ctx.R = sd.cwiseAbs2().asDiagonal();
	std::mt19937 rng(seed);
	std::normal_distribution<double> nz(0, 1);
	for (int i = 0; i < n; ++i)
	{
		const Eigen::Vector2d z = models::observe(m, truth.head<3>(), truth.segment<2>(3 + 2 * i)) +
		                          Eigen::Vector2d(sd[0] * nz(rng), sd[1] * nz(rng));
		s.obs.push_back({i, z, 3 + 2 * i});
	}
	return s;
}

/// The correlated case: ego at the origin, heading known exactly, position variance 0.04 per
/// axis; landmarks at (5, 0), (0, 5), (-5, 0), (0, -5) with variance 0.001; R = 0.01 I;
/// Cartesian readings. Every reading's innovation covariance is 0.051 I, and the x-parts of any
/// two readings are correlated by 0.04 (the shared ego position): rho = 0.78. `ox[i]` is
/// reading i's x-offset from its prediction, in standard deviations sqrt(0.051).
TScene correlatedScene(const std::vector<double>& ox)
{
	TScene s;
	const int n = int(ox.size());
	s.x = Eigen::VectorXd::Zero(3 + 2 * n);
	s.P = ekf::RowMatrixXd::Identity(3 + 2 * n, 3 + 2 * n) * 0.001;
	s.P.topLeftCorner<3, 3>() = Eigen::Vector3d(0.04, 0.04, 0.0).asDiagonal();
	s.ctx.R = 0.01 * Eigen::Matrix2d::Identity();
	const double a[4][2] = {{5, 0}, {0, 5}, {-5, 0}, {0, -5}};
	for (int i = 0; i < n; ++i)
	{
		s.x.segment<2>(3 + 2 * i) << a[i][0], a[i][1];
		const Eigen::Vector2d z = Eigen::Vector2d(a[i][0], a[i][1]) +
		                          Eigen::Vector2d(ox[size_t(i)] * std::sqrt(0.051), 0);
		s.obs.push_back({10 + i, z, 3 + 2 * i});
	}
	return s;
}

/// The gated sparse update at `confidence` (the `gate` method).
TUpdateResult gated(TScene& s, double confidence)
{
	TUpdateContext c = s.ctx;
	c.gate_threshold = gateThreshold2Dof(confidence);
	CSparseUpdateEngine plain;
	return plain.update(s.x, s.P, s.obs, c);
}

size_t count(const std::vector<bool>& v) { return size_t(std::count(v.begin(), v.end(), true)); }
}  // namespace

TEST(Jcbb, AJointlyCompatibleStepEqualsTheGate)
{
	for (auto m : {models::MeasurementModel::Cartesian, models::MeasurementModel::RangeBearing})
	{
		auto a = randomScene(m), b = randomScene(m);
		const auto ra = gated(a, 0.99);
		CJcbbUpdateEngine jcbb(0.99);
		const auto rb = jcbb.update(b.x, b.P, b.obs, b.ctx);
		EXPECT_EQ(ra.updates, 6u);
		EXPECT_EQ(rb.updates, 6u);
		EXPECT_EQ(rb.gated_out, 0u);
		EXPECT_EQ(jcbb.lastMrptAssociated(), 6u);
		EXPECT_EQ(count(jcbb.lastAccepted()), 6u);
		EXPECT_LT((a.x - b.x).cwiseAbs().maxCoeff(), 1e-12);
		EXPECT_LT((a.P - b.P).cwiseAbs().maxCoeff(), 1e-12);
		EXPECT_NEAR(ra.nis, rb.nis, 1e-12);
		EXPECT_NEAR(jcbb.lastJointNis(), rb.nis, 1e-9);  // the search's NIS is the update's
		EXPECT_LE(rb.nis, eval::chi2Quantile(0.99, 12));
	}
}

TEST(Jcbb, BearingAcrossPiIsWrapped)
{
	// A landmark straight behind the ego: predicted bearing pi - 0.01, measured -pi + 0.01
	// (0.02 rad apart once wrapped, 1 sigma). MRPT subtracts without wrapping; the engine must
	// hand it the reading next to its prediction.
	TScene s;
	s.x = Eigen::VectorXd::Zero(5);
	s.x.tail<2>() << -5 * std::cos(0.01), 5 * std::sin(0.01);
	s.P = ekf::RowMatrixXd::Identity(5, 5) * 1e-4;
	s.ctx.model = models::MeasurementModel::RangeBearing;
	s.ctx.R = Eigen::Vector2d(0.01, 4e-4).asDiagonal();
	s.obs.push_back({1, Eigen::Vector2d(5, -M_PI + 0.01), 3});
	auto g = s;
	const auto rg = gated(g, 0.99);
	CJcbbUpdateEngine jcbb(0.99);
	const auto r = jcbb.update(s.x, s.P, s.obs, s.ctx);
	EXPECT_EQ(rg.updates, 1u);
	EXPECT_EQ(r.updates, 1u);
	EXPECT_EQ(jcbb.lastMrptAssociated(), 1u);
	EXPECT_LT((s.x - g.x).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Jcbb, AGrossOutlierIsRejectedAsByTheGate)
{
	auto a = randomScene(models::MeasurementModel::Cartesian);
	a.obs[2].z += Eigen::Vector2d(5.0, 0.0);  // 5 m off
	auto b = a;
	const auto ra = gated(a, 0.99);
	CJcbbUpdateEngine jcbb(0.99);
	const auto rb = jcbb.update(b.x, b.P, b.obs, b.ctx);
	EXPECT_EQ(ra.gated_out, 1u);
	EXPECT_EQ(rb.gated_out, 1u);
	EXPECT_EQ(rb.updates, 5u);
	EXPECT_FALSE(jcbb.lastAccepted()[2]);
	EXPECT_EQ(jcbb.lastMrptAssociated(), 5u);  // MRPT's individual compatibility already
	EXPECT_LT((a.x - b.x).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_LT((a.P - b.P).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Jcbb, PassesTheGateOneByOneButNotJointly)
{
	const double conf = 0.99;
	// Each reading 2.5 sigma off (d^2 = 6.25 < chi2(0.99, 2) = 9.21), in opposite x directions
	// although a shared ego error would move both the same way: joint NIS of the pair
	// 2 * 6.25 / (1 - 0.78) = 57 > chi2(0.99, 4) = 13.3.
	{
		auto s = correlatedScene({2.5, -2.5});
		auto g = s;
		const auto rg = gated(g, conf);
		EXPECT_EQ(rg.updates, 2u);  // the gate takes both
		EXPECT_NEAR(rg.nis, 2 * 6.25 / (1 - 0.04 / 0.051), 1e-9);
		EXPECT_GT(rg.nis, eval::chi2Quantile(conf, 4));
		CJcbbUpdateEngine jcbb(conf);
		const auto r = jcbb.update(s.x, s.P, s.obs, s.ctx);
		EXPECT_EQ(jcbb.lastMrptAssociated(), 2u);  // MRPT's JCBB has no joint test
		EXPECT_EQ(r.updates, 1u);                  // the joint test keeps one of the two
		EXPECT_EQ(r.gated_out, 1u);
		EXPECT_NEAR(r.nis, 6.25, 1e-9);
	}
	// Control: the same offsets in the same direction are jointly compatible (NIS
	// 12.5 / (1 + 0.78) = 7.0): both used, as by the gate.
	{
		auto s = correlatedScene({2.5, 2.5});
		auto g = s;
		gated(g, conf);
		CJcbbUpdateEngine jcbb(conf);
		const auto r = jcbb.update(s.x, s.P, s.obs, s.ctx);
		EXPECT_EQ(r.updates, 2u);
		EXPECT_NEAR(r.nis, 2 * 6.25 / (1 + 0.04 / 0.051), 1e-9);
		EXPECT_LT((s.x - g.x).cwiseAbs().maxCoeff(), 1e-12);
	}
	// The pair first, then two readings that agree with the prediction: a +-2.5 sigma reading
	// is jointly incompatible even with one of them (NIS 16.2 > 13.3), so the largest jointly
	// compatible set is the two agreeing readings, and both of the pair are rejected.
	{
		auto s = correlatedScene({2.5, -2.5, 0, 0});
		auto g = s;
		EXPECT_EQ(gated(g, conf).updates, 4u);
		CJcbbUpdateEngine jcbb(conf);
		const auto r = jcbb.update(s.x, s.P, s.obs, s.ctx);
		EXPECT_EQ(jcbb.lastMrptAssociated(), 4u);
		EXPECT_EQ(r.updates, 2u);
		EXPECT_EQ(jcbb.lastAccepted(), (std::vector<bool>{false, false, true, true}));
		EXPECT_NEAR(r.nis, 0.0, 1e-12);
		EXPECT_EQ(s.x.head<3>().norm(), 0.0);  // zero innovations used: the ego did not move
	}
}

TEST(Jcbb, EmptyStepIsANoOpAndBadConfidenceIsAClearError)
{
	auto s = randomScene(models::MeasurementModel::Cartesian);
	const Eigen::VectorXd x0 = s.x;
	const ekf::RowMatrixXd P0 = s.P;
	CJcbbUpdateEngine jcbb(0.999);
	const auto r = jcbb.update(s.x, s.P, {}, s.ctx);
	EXPECT_EQ(r.updates, 0u);
	EXPECT_EQ(r.gated_out, 0u);
	EXPECT_EQ(r.nis, 0.0);
	EXPECT_TRUE(jcbb.lastAccepted().empty());
	EXPECT_EQ(s.x, x0);
	EXPECT_EQ(s.P, P0);
	for (double bad : {0.0, 1.0, -0.5, 1.5, std::nan("")})
	{
		try
		{
			CJcbbUpdateEngine e(bad);
			ADD_FAILURE() << "confidence " << bad << " accepted";
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("confidence"), std::string::npos) << e.what();
		}
	}
	EXPECT_THROW(CJcbbUpdateEngine(0.99, 0), std::invalid_argument);
	// A search cut by max_nodes keeps the best subset found so far (here: none yet), counted.
	auto t = randomScene(models::MeasurementModel::Cartesian);
	CJcbbUpdateEngine cut(0.999, 3);
	EXPECT_EQ(cut.update(t.x, t.P, t.obs, t.ctx).updates, 0u);
	EXPECT_EQ(cut.searchesTruncated(), 1u);
	EXPECT_EQ(jcbb.searchesTruncated(), 0u);
}

TEST(Jcbb, TheIniKeySelectsItAndNeedsAConfidence)
{
	const std::string base =
	    "[DynamicKFSLAM]\n"
	    "measurement_model = cartesian\n"
	    "Sigma_v = [1e-4 1e-4]\n"
	    "Sigma_xi = [0.1 0.1]\n"
	    "outlier_method = jcbb\n";
	const auto engineOf = [&](const std::string& extra)
	{
		mrpt::config::CConfigFileMemory ini(base + extra);
		CDynamicKFSLAM2D kf;
		kf.loadOptions(ini, "DynamicKFSLAM");
		return kf.updateEngine().name();
	};
	EXPECT_EQ(engineOf("innovation_gate = 0.999\n"), "jcbb");
	try
	{
		engineOf("");  // innovation_gate = 0: no confidence
		ADD_FAILURE() << "jcbb without a confidence accepted";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("jcbb"), std::string::npos) << e.what();
		EXPECT_NE(std::string(e.what()).find("[DynamicKFSLAM]"), std::string::npos) << e.what();
	}
	EXPECT_THROW(engineOf("innovation_gate = 1\n"), std::invalid_argument);
	EXPECT_THROW(engineOf("innovation_gate = 0.99\nstatic_update = mrpt\n"), std::invalid_argument);
}

namespace
{
mrpt::obs::CSensoryFrame::Ptr withRangeError(const mrpt::obs::CSensoryFrame::Ptr& sf, float dr)
{
	auto o = mrpt::obs::CObservationBearingRange::Create(
	    *sf->getObservationByClass<mrpt::obs::CObservationBearingRange>());
	o->sensedData[0].range += dr;
	auto out = mrpt::obs::CSensoryFrame::Create();
	out->insert(o);
	return out;
}
}  // namespace

TEST(Jcbb, EkfRunEqualsTheGatedRunAndRejectsTheOutlier)
{
	// The tiny scenario of DynamicGate (one moving object), a 3 m range error on the first
	// reading of step 12 (a tracked landmark): every other step is jointly compatible, so the
	// run with jcbb equals the gated run, step by step.
	dynslam_test::TinyScenarioOptions o;
	o.steps = 25;
	o.objects = 1;
	const auto sc = dynslam_test::makeTinyScenario(o);
	CDynamicKFSLAM2D gate, jcbb;
	for (CDynamicKFSLAM2D* f : {&gate, &jcbb})
	{
		f->options.measurement_model = models::MeasurementModel::RangeBearing;
		f->options.Sigma_v = o.Sigma_rb;
		f->options.innovation_gate = 0.999;
	}
	jcbb.options.outlier_method = "jcbb";
	gate.reset();
	jcbb.reset();
	ASSERT_EQ(jcbb.updateEngine().name(), "jcbb");
	size_t rejected = 0, updates = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		const auto sf = k == 12 ? withRangeError(sc.frames[k], 3.0f) : sc.frames[k];
		gate.processActionObservation(sc.actions[k], sf);
		jcbb.processActionObservation(sc.actions[k], sf);
		rejected += jcbb.getLastStepReport().gated_out;
		updates += jcbb.getLastStepReport().static_updates;
		EXPECT_EQ(jcbb.getLastStepReport().gated_out, gate.getLastStepReport().gated_out) << k;
	}
	EXPECT_EQ(rejected, 1u);
	EXPECT_GT(updates, 20u);
	const Eigen::VectorXd a = gate.fullMean().asEigen(), b = jcbb.fullMean().asEigen();
	ASSERT_EQ(a.size(), b.size());
	EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12);
}
