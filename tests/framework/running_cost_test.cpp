/** The running cost's operations: Gauss-Newton on a linear problem, marginalization (Schur
 * complement = the paper's projector formula), drop, and bad input. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/framework/running_cost.h>
#include <gtest/gtest.h>

#include <random>

#include "framework_test_utils.h"

using namespace dynslam::framework;
using dynslam_test::relErr;

namespace
{
/** Linear residual r = sum_i A_i x_i - b with information W (test-only term). */
class CLinearTerm : public CTerm
{
public:
	CLinearTerm(std::vector<TVarKey> k, std::vector<Eigen::MatrixXd> A, Eigen::VectorXd b,
	            Eigen::MatrixXd W)
	    : CTerm(std::move(k)), m_A(std::move(A)), m_b(std::move(b)), m_W(std::move(W))
	{
	}
	std::string name() const override { return "linear"; }
	TLinearization linearize(const std::vector<Eigen::VectorXd>& x) const override
	{
		TLinearization L;
		L.r = -m_b;
		for (size_t i = 0; i < x.size(); ++i) L.r += m_A[i] * x[i];
		L.J = m_A;
		L.W = m_W;
		return L;
	}

private:
	std::vector<Eigen::MatrixXd> m_A;
	Eigen::VectorXd m_b;
	Eigen::MatrixXd m_W;
};

Eigen::MatrixXd randn(std::mt19937& rng, int r, int c)
{
	std::normal_distribution<double> N(0, 1);
	Eigen::MatrixXd A(r, c);
	for (int i = 0; i < r; ++i)
		for (int j = 0; j < c; ++j) A(i, j) = N(rng);
	return A;
}

/** A small nonlinear SLAM problem: 4 ego poses, 5 landmarks, odometry, measurements. */
CRunningCost smallSlam(std::mt19937& rng)
{
	std::normal_distribution<double> N(0, 1);
	CRunningCost c;
	const Eigen::Vector3d u(1.0, 0.1, 0.05);
	Eigen::Vector3d x(0, 0, 0.2);
	for (int t = 0; t < 4; ++t)
	{
		c.addVariable(TVarKey::ego(t), x + 0.01 * Eigen::Vector3d(N(rng), N(rng), N(rng)));
		x = dynslam::models::composePose(x, u);
	}
	for (int l = 0; l < 5; ++l)
		c.addVariable(TVarKey::landmark(l), Eigen::Vector2d(1.5 * l, 3 + 0.5 * N(rng)));
	c.addTerm(CPriorTerm::fromCovariance(
	    {TVarKey::ego(0)}, {3}, c.value(TVarKey::ego(0)) + Eigen::Vector3d(0.01, 0, 0),
	    Eigen::Matrix3d(Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal())));
	for (int t = 0; t + 1 < 4; ++t)
		c.addTerm(std::make_shared<COdometryTerm>(
		    t, t + 1, u, Eigen::Matrix3d(Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal())));
	for (int t = 0; t < 4; ++t)
		for (int l = 0; l < 5; ++l)
		{
			const Eigen::Vector2d z = dynslam::models::cartesianObserve(
			                              c.value(TVarKey::ego(t)), c.value(TVarKey::landmark(l))) +
			                          0.01 * Eigen::Vector2d(N(rng), N(rng));
			c.addTerm(std::make_shared<CMeasurementTerm>(
			    t, TVarKey::landmark(l), z, dynslam::models::MeasurementModel::Cartesian,
			    Eigen::Matrix2d::Identity() * 1e-4));
		}
	return c;
}
}  // namespace

TEST(RunningCost, GaussNewtonOnLinearProblemConvergesInOneStep)
{
	std::mt19937 rng(11);
	for (auto solver : {SolverKind::Dense, SolverKind::Sparse})
	{
		CRunningCost c;
		const std::vector<TVarKey> k{TVarKey::landmark(0), TVarKey::landmark(1),
		                             TVarKey::landmark(2)};
		for (const auto& key : k) c.addVariable(key, Eigen::Vector2d(5, -3));
		// Stacked least squares: rows of [A0 A1 A2] x = b
		Eigen::MatrixXd Abig = Eigen::MatrixXd::Zero(0, 6), Wbig = Eigen::MatrixXd::Zero(0, 0);
		Eigen::VectorXd bbig(0);
		std::vector<std::vector<int>> sets{{0}, {0, 1}, {1, 2}, {2, 0}, {1}};
		for (const auto& s : sets)
		{
			const int m = 3;
			std::vector<TVarKey> keys;
			std::vector<Eigen::MatrixXd> A;
			Eigen::MatrixXd rowBlock = Eigen::MatrixXd::Zero(m, 6);
			for (int i : s)
			{
				keys.push_back(k[i]);
				A.push_back(randn(rng, m, 2));
				rowBlock.middleCols(2 * i, 2) = A.back();
			}
			const Eigen::VectorXd b = randn(rng, m, 1);
			const Eigen::MatrixXd W = dynslam_test::randomSpd(rng, m, 0.5, 20);
			c.addTerm(std::make_shared<CLinearTerm>(keys, A, b, W));
			Eigen::MatrixXd A2(Abig.rows() + m, 6);
			A2 << Abig, rowBlock;
			Abig = A2;
			Eigen::VectorXd b2(bbig.size() + m);
			b2 << bbig, b;
			bbig = b2;
			Eigen::MatrixXd W2 = Eigen::MatrixXd::Zero(Wbig.rows() + m, Wbig.cols() + m);
			W2.topLeftCorner(Wbig.rows(), Wbig.cols()) = Wbig;
			W2.bottomRightCorner(m, m) = W;
			Wbig = W2;
		}
		const Eigen::MatrixXd H = Abig.transpose() * Wbig * Abig;
		const Eigen::VectorXd xls = H.ldlt().solve(Abig.transpose() * Wbig * bbig);
		TGaussNewtonOptions o;
		o.solver = solver;
		const auto r1 = c.gaussNewtonStep(o);
		EXPECT_LT(relErr(c.stackedValues(), xls), 1e-12);
		if (solver == SolverKind::Dense)
		{
			EXPECT_LT(relErr(r1.covariance, H.inverse()), 1e-12);
		}
		const auto r2 = c.gaussNewtonStep(o);
		EXPECT_LT(r2.max_step, 1e-12);
		EXPECT_GT(r1.max_step, 1.0);
	}
}

TEST(RunningCost, GaussNewtonSparseEqualsDense)
{
	std::mt19937 rng(3);
	CRunningCost a = smallSlam(rng), b = a;
	TGaussNewtonOptions od, os;
	od.solver = SolverKind::Dense;
	os.solver = SolverKind::Sparse;
	for (int it = 0; it < 3; ++it)
	{
		a.gaussNewtonStep(od);
		b.gaussNewtonStep(os);
	}
	EXPECT_LT(relErr(a.stackedValues(), b.stackedValues()), 1e-12);
	const std::vector<TVarKey> q{TVarKey::ego(3), TVarKey::landmark(2)};
	EXPECT_LT(relErr(a.covariance(q, od), b.covariance(q, os)), 1e-10);
}

TEST(RunningCost, MarginalizationEqualsSchurComplementAndProjectorFormula)
{
	std::mt19937 rng(5);
	CRunningCost c = smallSlam(rng);
	for (int it = 0; it < 2; ++it) c.gaussNewtonStep();
	// Move off the optimum so the marginal has a non-zero gradient part.
	c.setValue(TVarKey::ego(1), c.value(TVarKey::ego(1)) + Eigen::Vector3d(0.02, -0.01, 0.003));
	const std::vector<TVarKey> M{TVarKey::ego(0), TVarKey::ego(1)};

	// Reference 1: Schur complement of the full information matrix (all other variables).
	Eigen::MatrixXd J;
	Eigen::VectorXd C;
	c.whitenedSystem(J, C);
	const Eigen::MatrixXd H = J.transpose() * J;
	const Eigen::VectorXd g = J.transpose() * C;
	std::vector<int> mIdx, kIdx;
	for (const auto& key : c.keys())
		for (int i = 0; i < c.dim(key); ++i)
			(key == M[0] || key == M[1] ? mIdx : kIdx).push_back(c.offset(key) + i);
	const Eigen::MatrixXd Hmm = H(mIdx, mIdx), Hkm = H(kIdx, mIdx);
	const Eigen::MatrixXd schur = H(kIdx, kIdx) - Hkm * Hmm.ldlt().solve(Hkm.transpose());

	// Reference 2: the paper's I - J_M (J_M^T J_M)^-1 J_M^T on all rows.
	Eigen::MatrixXd OmegaP;
	Eigen::VectorXd dP;
	dynslam::framework::projectorMarginal(J(Eigen::all, kIdx), J(Eigen::all, mIdx), C, OmegaP, dP);
	EXPECT_LT(relErr(schur, OmegaP), 1e-9);

	// The reduced cost (prior + untouched terms) has the same information on K.
	const std::vector<TVarKey> keysBefore = c.keys();
	const Eigen::VectorXd xBefore = c.stackedValues();
	auto prior = c.marginalize(M);
	ASSERT_TRUE(prior);
	EXPECT_FALSE(c.has(M[0]));
	Eigen::MatrixXd J2;
	Eigen::VectorXd C2;
	c.whitenedSystem(J2, C2);
	// c's storage order equals the order of kIdx (kept variables keep their relative order).
	EXPECT_LT(relErr(J2.transpose() * J2, schur), 1e-9);
	EXPECT_LT(relErr(J2.transpose() * C2, g(kIdx) - Hkm * Hmm.ldlt().solve(g(mIdx))), 1e-9);

	// A GN step on the reduced cost gives the K-part of the GN step on the full cost.
	const Eigen::VectorXd dFull = -H.ldlt().solve(g);
	c.gaussNewtonStep();
	Eigen::VectorXd xK = xBefore(kIdx) + dFull(kIdx);
	EXPECT_LT(relErr(c.stackedValues(), xK), 1e-9);
	// The projector formula's mean offset is that same K-part of the full GN step.
	EXPECT_LT(relErr(dP, dFull(kIdx)), 1e-8);
}

TEST(RunningCost, DropRemovesVariablesAndTheirTerms)
{
	std::mt19937 rng(7);
	CRunningCost c = smallSlam(rng);
	const size_t terms = c.terms().size();
	c.drop({TVarKey::landmark(3)});
	EXPECT_FALSE(c.has(TVarKey::landmark(3)));
	EXPECT_EQ(c.terms().size(), terms - 4);  // its 4 measurements
	EXPECT_EQ(c.totalDim(), 4 * 3 + 4 * 2);
	c.gaussNewtonStep();  // still well posed
	EXPECT_THROW(c.drop({TVarKey::landmark(3)}), std::out_of_range);
}

TEST(RunningCost, BadInputVariableReferencedBeforeItExists)
{
	CRunningCost c;
	c.addVariable(TVarKey::ego(0), Eigen::Vector3d::Zero());
	try
	{
		c.addTerm(std::make_shared<CMeasurementTerm>(0, TVarKey::landmark(4), Eigen::Vector2d(1, 1),
		                                             dynslam::models::MeasurementModel::Cartesian,
		                                             Eigen::Matrix2d::Identity()));
		FAIL() << "no exception";
	}
	catch (const std::invalid_argument& e)
	{
		EXPECT_NE(std::string(e.what()).find("landmark 4"), std::string::npos) << e.what();
	}
	EXPECT_THROW(c.value(TVarKey::ego(1)), std::out_of_range);
	EXPECT_THROW(c.addVariable(TVarKey::ego(0), Eigen::Vector3d::Zero()), std::invalid_argument);
	EXPECT_THROW(c.addVariable(TVarKey::ego(2), Eigen::Vector3d(0, std::nan(""), 0)),
	             std::invalid_argument);
	EXPECT_THROW(c.marginalize({TVarKey::ego(5)}), std::out_of_range);
}

TEST(RunningCost, BadInputSingularSystemUnobservableObjectPose)
{
	// An object pose whose rotation is unobservable: two coinciding time-0 features give a
	// feature-space residual with no information on dtheta.
	CRunningCost c;
	const TVarKey a0 = TVarKey::objectFeature(1, 0, 0), a1 = TVarKey::objectFeature(1, 1, 0);
	const TVarKey b0 = TVarKey::objectFeature(1, 0, 3), b1 = TVarKey::objectFeature(1, 1, 3);
	const TVarKey xi = TVarKey::objectPose(1, 3);
	for (const auto& k : {a0, a1, b0, b1}) c.addVariable(k, Eigen::Vector2d(2, 1));
	c.addVariable(xi, Eigen::Vector3d::Zero());
	c.addTerm(
	    CPriorTerm::fromCovariance({a0, a1, b0, b1}, {2, 2, 2, 2},
	                               Eigen::VectorXd::Constant(8, 1.0).cwiseProduct(
	                                   Eigen::VectorXd(Eigen::Vector2d(2, 1).replicate(4, 1))),
	                               Eigen::MatrixXd::Identity(8, 8) * 1e-2));
	TObjectPoseKeys k{xi, {a0, a1}, {b0, b1}, {0, 1}};
	c.addTerm(std::make_shared<CObjectPoseFeatureTerm>(k, Eigen::Matrix2d::Identity() * 0.1));
	try
	{
		c.gaussNewtonStep();
		FAIL() << "no exception";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("xi[obj 1, t 3]"), std::string::npos) << e.what();
	}
	// A pose with no term at all.
	CRunningCost d;
	d.addVariable(TVarKey::objectPose(2, 1), Eigen::Vector3d::Zero());
	EXPECT_THROW(d.gaussNewtonStep(), std::runtime_error);
	// The pseudo-inverse option returns finite values instead.
	TGaussNewtonOptions o;
	o.allow_singular = true;
	const auto r = c.gaussNewtonStep(o);
	EXPECT_TRUE(r.covariance.allFinite());
	EXPECT_TRUE(c.stackedValues().allFinite());
}
