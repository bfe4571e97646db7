/** First-estimate Jacobians (options.first_estimate_jacobians): off is bit-identical to the
 * default; on, the Jacobians are the models' derivatives at the first estimates, both update
 * paths agree, and the linearized system keeps the 3-dof unobservable subspace (global
 * translation and rotation) that the standard EKF loses; the option parses strictly. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam_test/numeric_jacobian.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/SVD>
#include <cmath>
#include <iostream>
#include <sstream>

#include "tiny_filter_setup.h"
#include "tiny_scenario.h"

using namespace dynslam;

namespace
{
const char* kIni = R"([DynamicKFSLAM]
measurement_model = range_bearing
Sigma_v = [1e-4 1e-6]
motion_noise = action
Sigma_0 = [0 0 0]
)";

std::string withKeys(const std::string& extra)
{
	return std::string(kIni) + extra + "\n[DynamicKFSLAM_KalmanFilter]\nmethod = kfEKFNaive\n";
}

/** Records the observation Jacobians MRPT's iteration asks for (static_update = mrpt); the
 * transition Jacobian of the prediction (ekf::propagate) is lastTransitionJacobian(). */
class CRecordingFilter : public CDynamicKFSLAM2D
{
public:
	struct TH
	{
		size_t slot;
		Eigen::Vector3d ego;            ///< ego mean when the Jacobian was asked for
		Eigen::Matrix<double, 2, 5> H;  ///< [Hx Hy]
	};
	mutable std::vector<TH> H;  ///< this step's observation Jacobians
	void clearRecords() { H.clear(); }

protected:
	void OnObservationJacobians(size_t s, KFMatrix_OxV& Hx, KFMatrix_OxF& Hy) const override
	{
		CDynamicKFSLAM2D::OnObservationJacobians(s, Hx, Hy);
		TH h;
		h.slot = s;
		h.ego = fullMean().asEigen().head<3>();
		h.H << Hx.asEigen(), Hy.asEigen();
		H.push_back(h);
	}
};

/** Null space dimension of M: singular values below 1e-9 of the largest. */
int nullity(const Eigen::MatrixXd& M, Eigen::VectorXd* sv = nullptr)
{
	const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M);
	const Eigen::VectorXd s = svd.singularValues();
	if (sv) *sv = s;
	int n = int(M.cols() - s.size());
	for (int i = 0; i < s.size(); ++i)
		if (s[i] < 1e-9 * s[0]) ++n;
	return n;
}
}  // namespace

TEST(Fej, OffIsBitIdenticalToDefaultOnDiffers)
{
	dynslam_test::TinyScenarioOptions o;
	o.objects = 2;
	o.steps = 40;
	o.landmarks = 20;
	const auto sc = dynslam_test::makeTinyScenario(o);
	for (const char* path : {"sparse", "mrpt"})
	{
		const std::string up = std::string("static_update = ") + path + "\n";
		CDynamicKFSLAM2D absent, off, on;
		mrpt::config::CConfigFileMemory c0(withKeys(up)),
		    c1(withKeys(up + "first_estimate_jacobians = false")),
		    c2(withKeys(up + "first_estimate_jacobians = true"));
		absent.loadOptions(c0);
		off.loadOptions(c1);
		on.loadOptions(c2);
		EXPECT_FALSE(absent.options.first_estimate_jacobians);
		EXPECT_FALSE(off.options.first_estimate_jacobians);
		EXPECT_TRUE(on.options.first_estimate_jacobians);
		double maxDiffOn = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			for (CDynamicKFSLAM2D* f : {&absent, &off, &on})
				f->processActionObservation(sc.actions[k], sc.frames[k]);
			ASSERT_TRUE(absent.fullMean().asEigen() == off.fullMean().asEigen())
			    << path << " step " << k;
			ASSERT_TRUE(absent.fullCov().asEigen() == off.fullCov().asEigen())
			    << path << " step " << k;
			ASSERT_EQ(absent.getLastStepReport().nis_static, off.getLastStepReport().nis_static);
			ASSERT_EQ(absent.fullMean().size(), on.fullMean().size());
			maxDiffOn = std::max(
			    maxDiffOn,
			    (absent.fullMean().asEigen() - on.fullMean().asEigen()).cwiseAbs().maxCoeff());
		}
		// Off records nothing; on records.
		EXPECT_FALSE(off.lastPredictedEgo().has_value());
		EXPECT_FALSE(off.firstEstimate(0).has_value());
		EXPECT_TRUE(on.lastPredictedEgo().has_value());
		std::cout << path << ": largest mean difference FEJ on vs off " << maxDiffOn << "\n";
		EXPECT_GT(maxDiffOn, 1e-6) << path;  // a different filter, not a no-op
		EXPECT_LT(maxDiffOn, 0.5) << path;   // but the same problem solved
	}
}

TEST(Fej, JacobiansAreModelDerivativesAtFirstEstimates)
{
	for (bool cart : {false, true})
	{
		dynslam_test::TinyScenarioOptions o;
		o.objects = 1;
		o.steps = 30;
		o.landmarks = 15;
		o.cartesian_noise = cart;
		o.Sigma_w = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();  // visible linearization errors
		const auto sc = dynslam_test::makeTinyScenario(o);
		CRecordingFilter f;
		dynslam_test::configureTinyFilter(f, o, true, false);
		std::map<int32_t, Eigen::Vector2d> initMean;  // landmark mean at the end of its first step
		std::optional<Eigen::Vector3d> prevPred;
		size_t nH = 0, nHdiffer = 0, nFdiffer = 0;
		for (size_t k = 0; k < sc.actions.size(); ++k)
		{
			f.clearRecords();
			const Eigen::Vector3d xPrev = f.fullMean().asEigen().head<3>();
			f.processActionObservation(sc.actions[k], sc.frames[k]);
			ASSERT_TRUE(f.lastPredictedEgo().has_value());
			const Eigen::Vector3d pred = *f.lastPredictedEgo();
			// Transition: heading column from the predicted positions p_{k|k-1} - p_{k-1|k-2}.
			ASSERT_TRUE(f.lastTransitionJacobian().has_value());
			const Eigen::Matrix3d F = *f.lastTransitionJacobian();
			if (prevPred)
			{
				Eigen::Matrix3d Fexp = Eigen::Matrix3d::Identity();
				Fexp(0, 2) = -(pred[1] - (*prevPred)[1]);
				Fexp(1, 2) = pred[0] - (*prevPred)[0];
				EXPECT_LT((F - Fexp).cwiseAbs().maxCoeff(), 1e-12) << "step " << k;
				// The standard column, from p_{k|k-1} - p_{k-1|k-1}, differs by the last update.
				if ((prevPred->head<2>() - xPrev.head<2>()).norm() > 1e-6) ++nFdiffer;
			}
			prevPred = pred;
			// Measurement Jacobians: at the predicted ego and the landmark's first estimate.
			for (const auto& h : f.H)
			{
				const int32_t id = f.getSlots()[h.slot].id;
				ASSERT_TRUE(h.ego == pred) << "ego at the update is x_{k|k-1}";
				const auto fe = f.firstEstimate(id);
				ASSERT_TRUE(fe.has_value()) << "landmark " << id;
				ASSERT_TRUE(initMean.count(id));
				EXPECT_TRUE(*fe == initMean.at(id))
				    << "first estimate = mean at the end of its first step";
				const auto model = f.options.measurement_model;
				auto hfun = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd
				{ return models::observe(model, v.head<3>(), v.tail<2>()); };
				Eigen::VectorXd at(5);
				at << pred, *fe;
				EXPECT_TRUE(dynslam_test::jacobianMatches(h.H, hfun, at, 1e-6));
				Eigen::VectorXd cur(5);
				const size_t si = 3 + 2 * h.slot;
				cur << pred, f.fullMean()[si],
				    f.fullMean()[si + 1];  // (after the update: only to show a difference)
				++nH;
				if (dynslam_test::relativeError(h.H, dynslam_test::numericJacobian(hfun, cur)) >
				    1e-5)
					++nHdiffer;
			}
			for (const auto& lm : f.getStaticLandmarks()) initMean.emplace(lm.id, lm.mean);
		}
		std::cout << (cart ? "cartesian" : "range-bearing") << ": " << nH
		          << " measurement Jacobians, " << nHdiffer
		          << " differ from those at the current estimate; " << nFdiffer << " of "
		          << sc.actions.size() - 1
		          << " transition Jacobians differ from the standard one\n";
		EXPECT_GT(nH, 100u);
		EXPECT_GT(nHdiffer, nH / 2);  // the test is not vacuous
		EXPECT_GT(nFdiffer, size_t(sc.actions.size()) / 2);
	}
}

TEST(Fej, SparseUpdateEqualsMrptUpdate)
{
	for (bool cart : {false, true})
	{
		dynslam_test::TinyScenarioOptions o;
		o.objects = 2;
		o.steps = 40;
		o.landmarks = 20;
		o.cartesian_noise = cart;
		o.Sigma_w = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
		const auto sc = dynslam_test::makeTinyScenario(o);
		CDynamicKFSLAM2D a, b;
		dynslam_test::configureTinyFilter(a, o, true, false);
		dynslam_test::configureTinyFilter(b, o, true, true);
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
		}
		std::cout << (cart ? "cartesian" : "range-bearing")
		          << ": FEJ sparse vs MRPT worst relative " << worst << "\n";
		EXPECT_LT(worst, 1e-9);
	}
}

TEST(Fej, KeepsTheThreeDofUnobservableSubspace)
{
	// Static world, every landmark in view at every step (so the state at the end of step 0
	// holds them all): stack the observability matrix M = [H_k F_k ... F_1]_k of the
	// linearized system the filter used, over the state at the end of step 0.
	for (bool cart : {false, true})
	{
		dynslam_test::TinyScenarioOptions o;
		o.landmarks = 6;
		o.steps = 15;
		o.range = 100;
		o.cartesian_noise = cart;
		o.Sigma_w = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
		const auto sc = dynslam_test::makeTinyScenario(o);
		for (bool fej : {false, true})
		{
			CRecordingFilter f;
			dynslam_test::configureTinyFilter(f, o, fej, false);
			f.processActionObservation(sc.actions[0], sc.frames[0]);
			const int n = int(f.fullMean().size());
			ASSERT_EQ(n, 3 + 2 * o.landmarks);
			Eigen::VectorXd x0 = f.fullMean().asEigen();
			Eigen::MatrixXd Phi = Eigen::MatrixXd::Identity(n, n), M(0, n);
			for (size_t k = 1; k < sc.actions.size(); ++k)
			{
				f.clearRecords();
				f.processActionObservation(sc.actions[k], sc.frames[k]);
				ASSERT_TRUE(f.lastTransitionJacobian().has_value());
				ASSERT_EQ(int(f.fullMean().size()), n);
				Phi.topRows<3>() = *f.lastTransitionJacobian() * Phi.topRows<3>();
				ASSERT_EQ(int(f.H.size()), o.landmarks);
				for (const auto& h : f.H)
				{
					Eigen::MatrixXd Hk = Eigen::MatrixXd::Zero(2, n);
					Hk.leftCols<3>() = h.H.leftCols<3>();
					Hk.middleCols<2>(3 + 2 * h.slot) = h.H.rightCols<2>();
					M.conservativeResize(M.rows() + 2, n);
					M.bottomRows<2>() = Hk * Phi;
				}
			}
			Eigen::VectorXd sv;
			const int nul = nullity(M, &sv);
			// The rotation about the origin at the first estimates (the ego's at step 0 and the
			// landmarks' at their initialization, both = the state at the end of step 0).
			Eigen::VectorXd rot(n);
			for (int i = 0; i < n; i += (i == 0 ? 3 : 2))
			{
				rot[i] = -x0[i + 1];
				rot[i + 1] = x0[i];
			}
			rot[2] = 1;
			const double rotResidual = (M * rot).norm() / (sv[0] * rot.norm());
			std::cout << (cart ? "cartesian" : "range-bearing") << (fej ? " FEJ" : " standard")
			          << ": nullity " << nul << ", smallest singular values / largest "
			          << (sv.tail<4>() / sv[0]).transpose() << ", |M n_rot| / (s_max |n_rot|) "
			          << rotResidual << "\n";
			if (fej)
			{
				EXPECT_EQ(nul, 3);
				EXPECT_LT(rotResidual, 1e-12);
			}
			else
			{
				EXPECT_EQ(nul, 2);  // the heading became (spuriously) observable
				EXPECT_GT(rotResidual, 1e-7);
			}
		}
	}
}

TEST(Fej, OptionParsesStrictlyAndDumps)
{
	auto load = [](const std::string& extra, CDynamicKFSLAM2D& f) -> std::string
	{
		mrpt::config::CConfigFileMemory c(withKeys(extra));
		try
		{
			f.loadOptions(c);
		}
		catch (const std::exception& e)
		{
			return e.what();
		}
		return "";
	};
	CDynamicKFSLAM2D f;
	EXPECT_EQ(load("first_estimate_jacobians = true", f), "");
	EXPECT_TRUE(f.options.first_estimate_jacobians);
	std::ostringstream os;
	f.options.dumpToTextStream(os);
	EXPECT_NE(os.str().find("first_estimate_jacobians       = true"), std::string::npos)
	    << os.str();
	// The dump loads back.
	std::string dumped = os.str();
	dumped = dumped.substr(dumped.find("measurement_model"));
	mrpt::config::CConfigFileMemory c2("[X]\n" + dumped);
	CDynamicKFSLAM2D::TOptions o2;
	o2.loadFromConfigFile(c2, "X");
	EXPECT_TRUE(o2.first_estimate_jacobians);

	EXPECT_EQ(load("first_estimate_jacobians = false", f), "");
	EXPECT_FALSE(f.options.first_estimate_jacobians);
	EXPECT_EQ(load("", f), "");
	EXPECT_FALSE(f.options.first_estimate_jacobians);
	CDynamicKFSLAM2D g;
	for (const char* bad : {"maybe", "2", "truee"})
	{
		const auto e = load(std::string("first_estimate_jacobians = ") + bad, g);
		EXPECT_NE(e.find("[DynamicKFSLAM] first_estimate_jacobians = '" + std::string(bad) + "'"),
		          std::string::npos)
		    << e;
		EXPECT_NE(e.find("not a boolean"), std::string::npos) << e;
	}
}
