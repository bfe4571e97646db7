/** object_model = mm (multiple-model objects, issue 28; estimator/multiple_model.h): each mode's
 * transition Jacobian against central differences (3-dof and translation-only poses, rotations
 * next to +-pi), the modes' meaning (stationary stops, turn = ctrv, manoeuvre = cv with its own
 * noise), the registry and the options (read, dumped, bad input naming the key). The filter's
 * behaviour on the tunnel scenarios is test_multiple_model_tunnel.cpp. */
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/multiple_model.h>
#include <dynslam/estimator/seam_registries.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "model_test_utils.h"
#include "object_model_setup.h"

using namespace dynslam;
using dynslam_test::errorOf;
using dynslam_test::numericJ;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using estimator::CMultipleModel;
using estimator::TCvParams;

namespace
{
TCvParams params()
{
	TCvParams p;
	p.dt = 0.4;
	p.accel_psd = Eigen::Vector3d(0.1, 0.2, 0.01);
	p.mm_manoeuvre_psd = Eigen::Vector3d(3, 5, 0.2);
	return p;
}
}  // namespace

TEST(MultipleModel, ModeJacobiansMatchCentralDifferences)
{
	const CMultipleModel m(params());
	std::mt19937 g(2804);
	std::uniform_real_distribution<double> U(-2, 2);
	double worst = 0;
	for (const int d : {3, 2})
		for (int trial = 0; trial < 30; ++trial)
		{
			VectorXd s(2 * d);
			for (int i = 0; i < 2 * d; ++i) s[i] = 5 * U(g);
			if (d == 3)
			{
				s[2] = trial % 3 == 0 ? M_PI - 1e-4 : models::wrapToPi(s[2]);
				s[5] = 0.5 * U(g);
			}
			const std::vector<int> angles = d == 3 ? std::vector<int>{2} : std::vector<int>{};
			for (int j = 0; j < m.modeCount(); ++j)
			{
				MatrixXd J, Q;
				m.predictMode(j, s, &J, &Q);
				const MatrixXd Jn = numericJ([&](const VectorXd& v)
				                             { return m.predictMode(j, v, nullptr, nullptr); },
				                             s, angles);
				const double e = (J - Jn).cwiseAbs().maxCoeff() / std::max(1.0, Jn.norm());
				worst = std::max(worst, e);
				EXPECT_LT(e, 1e-6) << m.modeName(j) << " d " << d << " trial " << trial;
				EXPECT_EQ(Q.rows(), 2 * d);
			}
		}
	std::printf("[  worst   ] mm mode Jacobians: %.3g\n", worst);
}

TEST(MultipleModel, ModesAreStationaryCvTurnAndManoeuvre)
{
	const TCvParams p = params();
	const CMultipleModel m(p);
	ASSERT_EQ(m.modeCount(), 4);
	EXPECT_EQ(m.modeName(CMultipleModel::Stationary), "stationary");
	EXPECT_EQ(m.modeName(CMultipleModel::Manoeuvre), "manoeuvre");
	EXPECT_THROW(m.modeName(4), std::out_of_range);
	VectorXd s(6);
	s << 1, 2, 0.3, 4, -1, 0.2;
	MatrixXd F, Q, Fr, Qr;
	// stationary: the pose stays, the velocity is 0
	const VectorXd st = m.predictMode(CMultipleModel::Stationary, s, &F, &Q);
	EXPECT_EQ(st.head(3), s.head(3));
	EXPECT_EQ(st.tail(3), VectorXd::Zero(3));
	// cv and turn: the cv and ctrv steps with cv_accel_psd; manoeuvre: cv with its own noise
	const VectorXd cv = m.predictMode(CMultipleModel::Cv, s, &F, &Q);
	EXPECT_LT((cv - models::cvPredict(s, p.dt, &Fr)).norm(), 1e-15);
	EXPECT_LT((Q - models::cvProcessNoise(p.accel_psd, p.dt)).norm(), 1e-15);
	const VectorXd turn = m.predictMode(CMultipleModel::Turn, s, &F, &Q);
	EXPECT_LT((turn - models::ctrvPredict(s, p.dt)).norm(), 1e-15);
	EXPECT_GT((turn - cv).norm(), 1e-3);  // omega = 0.2 rad/s turns the velocity
	const VectorXd man = m.predictMode(CMultipleModel::Manoeuvre, s, &F, &Q);
	EXPECT_LT((man - cv).norm(), 1e-15);
	EXPECT_LT((Q - models::cvProcessNoise(p.mm_manoeuvre_psd, p.dt)).norm(), 1e-15);
	// switching: rows sum to 1, stay 1 - mm_switch_prob; equal start probabilities
	const MatrixXd Pi = m.modeTransition();
	EXPECT_NEAR(Pi(1, 1), 1 - p.mm_switch_prob, 1e-15);
	EXPECT_LT((Pi.rowwise().sum() - VectorXd::Ones(4)).norm(), 1e-15);
	EXPECT_LT((m.initialModeProbabilities() - VectorXd::Constant(4, 0.25)).norm(), 1e-15);
	// the registry: object-centric, the EKF and Alg. 1 (not the window back-ends)
	const auto& caps = estimator::objectMotionModels().caps("mm");
	EXPECT_TRUE(caps.object_centric);
	EXPECT_TRUE(caps.framework);
	EXPECT_FALSE(caps.window);
}

TEST(MultipleModel, OptionsAndBadInput)
{
	const auto load = [](const std::string& extra)
	{ return dynslam_test::loadCartesianFilter(extra)->objectMotionModel().name(); };
	const std::string mm = "object_model = mm\n[ObjectModel]\ncv_dt = 0.5\n";
	EXPECT_EQ(load(mm), "mm");
	EXPECT_NE(errorOf([&] { load("object_model = mm\n"); }).find("cv_dt"), std::string::npos);
	for (const char* bad : {"0", "1", "1.5", "-0.1"})
	{
		const std::string e =
		    errorOf([&] { load(mm + "[ObjectModel]\nmm_switch_prob = " + bad + "\n"); });
		EXPECT_NE(e.find("mm_switch_prob"), std::string::npos) << bad << ": '" << e << "'";
	}
	for (const char* bad : {"[0 1 1]", "[1 -1 1]", "[1 1]"})
	{
		const std::string e =
		    errorOf([&] { load(mm + "[ObjectModel]\nmm_manoeuvre_psd = " + bad + "\n"); });
		EXPECT_NE(e.find("mm_manoeuvre_psd"), std::string::npos) << bad << ": '" << e << "'";
	}
	const auto f = dynslam_test::loadCartesianFilter(
	    mm + "[ObjectModel]\nmm_switch_prob = 0.1\nmm_manoeuvre_psd = [1 2 0.3]\n");
	EXPECT_EQ(f->options.cv.mm_switch_prob, 0.1);
	EXPECT_EQ(f->options.cv.mm_manoeuvre_psd, Eigen::Vector3d(1, 2, 0.3));
	EXPECT_EQ(f->objectModeNames(),
	          (std::vector<std::string>{"stationary", "cv", "turn", "manoeuvre"}));
	std::ostringstream dump;
	f->options.dumpToTextStream(dump);
	EXPECT_NE(dump.str().find("mm_switch_prob                 = 0.1"), std::string::npos);
	EXPECT_NE(dump.str().find("mm_manoeuvre_psd               = [1 2 0.3]"), std::string::npos);
	EXPECT_TRUE(dynslam_test::loadCartesianFilter("object_model = cv\n[ObjectModel]\ncv_dt = 0.5\n")
	                ->objectModeNames()
	                .empty());
}
