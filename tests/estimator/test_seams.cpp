/** Each seam of the estimator core has a second implementation here, plugged into the filter
 * with nothing else changed (doc/architecture.md): a router with another ID convention, an
 * object motion model of the tests' own (in the EKF and in Alg. 1, which must still agree), and
 * a dense Joseph-form update engine. */
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/framework/CAlg1Backend.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Cholesky>
#include <map>

#include "tiny_scenario.h"

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
const std::string kIni = dynslam_test::script::kFilterKeys +
                         "Sigma_0 = [1e-6 1e-6 1e-8]\n"
                         "Sigma_xi = [0.1 0.1]\n"
                         "[DynamicKFSLAM_KalmanFilter]\n"
                         "method = kfEKFNaive\n"
                         "[Framework]\n"
                         "backend = alg1\n";

dynslam_test::TinyScenario scenario() { return dynslam_test::makeTwoObjectScenario(25, 7); }

double relDiff(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B)
{
	if (A.rows() != B.rows() || A.cols() != B.cols()) return 1e300;
	return (A - B).cwiseAbs().maxCoeff() / std::max(B.cwiseAbs().maxCoeff(), 1e-300);
}

// --- 1. a router with another ID convention ----------------------------------------------
/** Static landmarks 0..4999; feature k of object j is 5000 + 100 j + k. */
class CTestRouter : public IMeasurementRouter
{
public:
	std::string name() const override { return "test_ids"; }
	void validate(const std::vector<TReading>& rs, const std::string& who) const override
	{
		for (const auto& r : rs)
			if (r.id < 0) throw std::runtime_error(who + ": negative ID");
	}
	TRoutedStep route(int step, const std::vector<TReading>& rs,
	                  const std::function<bool(int32_t)>& known) override
	{
		TRoutedStep out;
		for (const auto& r : rs)
		{
			TRoutedReading m;
			m.reading = r;
			if (r.id < 5000)
				m.route = known(r.id) ? Route::StaticKnown : Route::StaticNew;
			else
			{
				m.object = (r.id - 5000) / 100;
				m.feature = (r.id - 5000) % 100;
				const auto role = m_reg.registerReading(m.object, r.id, m.feature, step);
				m.route = role == FeatureRole::FirstSighting ? Route::ObjectFirstSighting
				          : role == FeatureRole::TimeT       ? Route::ObjectTimeT
				                                             : Route::Skip;
				if (m.route == Route::Skip) ++out.skipped_unknown_object_feature;
			}
			out.readings.push_back(m);
		}
		return out;
	}
	const CObjectRegistry& registry() const override { return m_reg; }
	CObjectRegistry& registry() override { return m_reg; }
	int32_t featureId(int32_t o, int32_t k) const override { return 5000 + 100 * o + k; }
	void reset() override { m_reg.clear(); }

private:
	CObjectRegistry m_reg;
};

mrpt::obs::CSensoryFrame::Ptr remapIds(const mrpt::obs::CSensoryFrame::Ptr& sf)
{
	const auto in = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	*obs = *in;
	for (auto& m : obs->sensedData)
		if (ids::isObjectFeature(m.landmarkID))
			m.landmarkID = 5000 + 100 * ids::objectOf(m.landmarkID) + ids::featureOf(m.landmarkID);
	auto out = mrpt::obs::CSensoryFrame::Create();
	out->insert(obs);
	return out;
}
}  // namespace

TEST(Seams, RouterWithAnotherIdConventionGivesTheSameFilter)
{
	const auto sc = scenario();
	mrpt::config::CConfigFileMemory ini(kIni);
	CDynamicKFSLAM2D a, b;
	a.loadOptions(ini, "DynamicKFSLAM");
	b.loadOptions(ini, "DynamicKFSLAM");
	b.setRouter(std::make_unique<CTestRouter>());
	b.reset();
	EXPECT_EQ(b.router().name(), "test_ids");
	size_t objectSteps = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		a.processActionObservation(sc.actions[k], sc.frames[k]);
		b.processActionObservation(sc.actions[k], remapIds(sc.frames[k]));
		ASSERT_EQ(a.fullMean().size(), b.fullMean().size()) << "step " << k;
		EXPECT_EQ(relDiff(b.fullMean().asEigen(), a.fullMean().asEigen()), 0.0) << "step " << k;
		EXPECT_EQ(relDiff(b.fullCov().asEigen(), a.fullCov().asEigen()), 0.0) << "step " << k;
		objectSteps += a.getLastStepReport().object_poses_added;
	}
	EXPECT_GT(objectSteps, 10u);  // the objects were seen and tracked
	ASSERT_EQ(a.getObjectTracks().size(), b.getObjectTracks().size());
	for (const auto& f : b.getObjectFeatures()) EXPECT_EQ(f.id, 5000 + 100 * f.object + f.feature);
}

// --- 2. an object motion model of the tests' own ------------------------------------------
namespace
{
/** "The object keeps its pose": xi_t - xi_{t-1} = 0 + n, n ~ N(0, 0.05 I). */
class CConstantPoseModel : public IObjectMotionModel
{
public:
	std::string name() const override { return "constant_pose"; }
	int posesNeeded() const override { return 2; }
	std::vector<TPseudoMeasurement> select(int32_t obj, int step, const std::vector<int>& steps,
	                                       int dim) const override
	{
		const bool now = std::count(steps.begin(), steps.end(), step) == 1;
		const bool before = std::count(steps.begin(), steps.end(), step - 1) == 1;
		if (!now || !before) return {};
		TPseudoMeasurement m;
		m.object = obj;
		m.steps = {step - 1, step};
		m.dim = dim;
		m.R = Eigen::MatrixXd::Identity(dim, dim) * 0.05;
		return {m};
	}
	Eigen::VectorXd residual(const TPseudoMeasurement& m, const std::vector<Eigen::VectorXd>& p,
	                         std::vector<Eigen::MatrixXd>* J) const override
	{
		Eigen::VectorXd r = p[1] - p[0];
		if (m.dim == 3) r[2] = models::wrapToPi(r[2]);
		if (J)
			*J = {-Eigen::MatrixXd::Identity(m.dim, m.dim),
			      Eigen::MatrixXd::Identity(m.dim, m.dim)};
		return r;
	}
};

/** Max relative difference of the labelled states (means, covariances) of the two filters. */
std::pair<double, double> compareLabelled(const CDynamicKFSLAM2D& ekf,
                                          const framework::CAlg1Backend& alg)
{
	Eigen::VectorXd xe, xa;
	Eigen::MatrixXd Pe, Pa;
	std::vector<std::string> le, la;
	ekf.getStateWithoutPads(xe, Pe, &le);
	alg.getLabelledState(xa, Pa, la);
	if (le.size() != la.size()) return {1e300, 1e300};
	std::map<std::string, int> where;
	for (size_t i = 0; i < le.size(); ++i) where[le[i]] = int(i);
	std::vector<int> perm;
	for (const auto& l : la)
	{
		if (!where.count(l)) return {1e300, 1e300};
		perm.push_back(where[l]);
	}
	Eigen::VectorXd dx = xa - xe(perm);
	for (size_t i = 0; i < la.size(); ++i)
		if (la[i].find("theta") != std::string::npos) dx[i] = models::wrapToPi(dx[i]);
	const double em = dx.cwiseAbs().maxCoeff() / std::max(xe.cwiseAbs().maxCoeff(), 1e-300);
	return {em, relDiff(Pa, Eigen::MatrixXd(Pe(perm, perm)))};
}
}  // namespace

TEST(Seams, ObjectMotionModelOfTheTestsActsAlikeInTheEkfAndAlg1)
{
	const auto sc = scenario();
	mrpt::config::CConfigFileMemory ini(kIni);
	CDynamicKFSLAM2D ekf, plain;
	ekf.loadOptions(ini, "DynamicKFSLAM");
	plain.loadOptions(ini, "DynamicKFSLAM");
	ekf.setObjectMotionModel(std::make_unique<CConstantPoseModel>());
	ekf.reset();
	framework::TBackendOptions bo;
	bo.loadFromConfigFile(ini, "Framework");
	framework::CAlg1Backend alg(bo);
	alg.setObjectMotionModel(std::make_shared<CConstantPoseModel>());
	alg.reset();
	double worstMean = 0, worstCov = 0;
	size_t applied = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		ekf.processActionObservation(sc.actions[k], sc.frames[k]);
		plain.processActionObservation(sc.actions[k], sc.frames[k]);
		alg.processActionObservation(sc.actions[k], sc.frames[k]);
		const auto [em, ec] = compareLabelled(ekf, alg);
		worstMean = std::max(worstMean, em);
		worstCov = std::max(worstCov, ec);
		applied += ekf.getLastStepReport().smoothing_updates;
		EXPECT_EQ(ekf.getLastStepReport().smoothing_updates,
		          alg.getLastStepReport().smoothing_updates);
	}
	EXPECT_GT(applied, 10u);
	EXPECT_LT(worstMean, 1e-9);
	EXPECT_LT(worstCov, 1e-9);
	// The model acted: the object poses differ from the filter without it.
	const auto a = ekf.getObjectTracks(), b = plain.getObjectTracks();
	double d = 0;
	for (const auto& [obj, tr] : a)
		d = std::max(d, (tr.poses.back().mean - b.at(obj).poses.back().mean).norm());
	EXPECT_GT(d, 1e-3);
}

// --- 3. an update engine of the tests' own ----------------------------------------------
namespace
{
/** The textbook dense EKF update in Joseph form, counting its calls. */
class CDenseJosephEngine : public IUpdateEngine
{
public:
	int calls = 0;
	std::string name() const override { return "dense_joseph"; }
	TUpdateResult update(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<ekf::RowMatrixXd> P,
	                     const std::vector<TStaticObservation>& obs,
	                     const TUpdateContext& ctx) override
	{
		++calls;
		TUpdateResult res;
		const Eigen::Index n = x.size(), m = 2 * Eigen::Index(obs.size());
		if (m == 0) return res;
		Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, n), R = Eigen::MatrixXd::Zero(m, m);
		Eigen::VectorXd nu(m);
		for (size_t j = 0; j < obs.size(); ++j)
		{
			models::Matrix23d Jx;
			Eigen::Matrix2d Jf;
			const int i = obs[j].index;
			const Eigen::Vector2d zh =
			    models::observe(ctx.model, x.head<3>(), x.segment<2>(i), &Jx, &Jf);
			nu.segment<2>(2 * j) = models::innovation(ctx.model, obs[j].z, zh);
			H.block<2, 3>(2 * j, 0) = Jx;
			H.block<2, 2>(2 * j, i) = Jf;
			R.block<2, 2>(2 * j, 2 * j) = ctx.R;
		}
		const Eigen::MatrixXd Pd = P;
		const Eigen::MatrixXd S = H * Pd * H.transpose() + R;
		const Eigen::MatrixXd K = Pd * H.transpose() * S.inverse();
		const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(n, n) - K * H;
		x += K * nu;
		P = IKH * Pd * IKH.transpose() + K * R * K.transpose();
		res.updates = obs.size();
		res.nis = nu.dot(S.ldlt().solve(nu));
		res.nis_dof = size_t(m);
		return res;
	}
};
}  // namespace

TEST(Seams, UpdateEngineOfTheTestsEqualsTheSparseEngine)
{
	const auto sc = scenario();
	mrpt::config::CConfigFileMemory ini(kIni);
	CDynamicKFSLAM2D a, b;
	a.loadOptions(ini, "DynamicKFSLAM");
	b.loadOptions(ini, "DynamicKFSLAM");
	auto engine = std::make_unique<CDenseJosephEngine>();
	const CDenseJosephEngine* e = engine.get();
	b.setUpdateEngine(std::move(engine));
	b.loadOptions(ini, "DynamicKFSLAM");  // kept by loadOptions / reset
	EXPECT_EQ(b.updateEngine().name(), "dense_joseph");
	EXPECT_EQ(a.updateEngine().name(), "sparse");
	double worst = 0;
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		a.processActionObservation(sc.actions[k], sc.frames[k]);
		b.processActionObservation(sc.actions[k], sc.frames[k]);
		worst = std::max(worst, relDiff(b.fullMean().asEigen(), a.fullMean().asEigen()));
		worst = std::max(worst, relDiff(b.fullCov().asEigen(), a.fullCov().asEigen()));
		EXPECT_EQ(a.getLastStepReport().static_updates, b.getLastStepReport().static_updates);
		EXPECT_NEAR(a.getLastStepReport().nis_static, b.getLastStepReport().nis_static, 1e-8);
	}
	EXPECT_EQ(e->calls, int(sc.actions.size()));
	EXPECT_LT(worst, 1e-9);
	EXPECT_GT(worst, 0.0);  // a different computation, not the same code
}
