/** Every residual term of the framework (terms.h): its Jacobians dr/dx_i against central
 * differences taken through each block's plus (blockPlus, the retraction the Gauss-Newton
 * step uses), in the spirit of GTSAM's EXPECT_CORRECT_FACTOR_JACOBIANS; and its information
 * W symmetric positive semi-definite. Linearization points include headings next to +-pi, so
 * a perturbation crosses the cut. */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/constant_turn_rate.h>
#include <dynslam/framework/object_motion_terms.h>
#include <dynslam/framework/terms.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <sstream>

using namespace dynslam;
using namespace dynslam::framework;

namespace
{
/** Central difference of the residual with respect to block i, through blockPlus; residual
 * differences are wrapped (angle rows differ by 2 pi across the cut, other rows are tiny). */
Eigen::MatrixXd numericJ(const CTerm& t, std::vector<Eigen::VectorXd> x, size_t i, double h = 1e-6)
{
	const Eigen::VectorXd xi = x[i];
	const Eigen::Index d = xi.size();
	Eigen::MatrixXd J(t.linearize(x).r.size(), d);
	for (Eigen::Index j = 0; j < d; ++j)
	{
		const Eigen::VectorXd e = Eigen::VectorXd::Unit(d, j) * h;
		x[i] = blockPlus(t.keys()[i].kind, xi, e);
		const Eigen::VectorXd rp = t.linearize(x).r;
		x[i] = blockPlus(t.keys()[i].kind, xi, -e);
		const Eigen::VectorXd rm = t.linearize(x).r;
		Eigen::VectorXd dr = rp - rm;
		for (Eigen::Index k = 0; k < dr.size(); ++k) dr[k] = models::wrapToPi(dr[k]);
		J.col(j) = dr / (2 * h);
	}
	return J;
}

/** Checks every block's Jacobian and W; returns the worst relative Jacobian error. */
double checkTerm(const CTerm& t, const std::vector<Eigen::VectorXd>& x, double tol = 1e-6)
{
	const TLinearization L = t.linearize(x);
	EXPECT_EQ(L.J.size(), t.keys().size()) << t.name();
	EXPECT_EQ(L.W.rows(), L.r.size()) << t.name();
	EXPECT_LT((L.W - L.W.transpose()).cwiseAbs().maxCoeff(), 1e-9 * L.W.cwiseAbs().maxCoeff())
	    << t.name();
	const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (L.W + L.W.transpose()));
	EXPECT_GE(es.eigenvalues().minCoeff(), -1e-9 * es.eigenvalues().cwiseAbs().maxCoeff())
	    << t.name();
	double worst = 0;
	for (size_t i = 0; i < t.keys().size(); ++i)
	{
		const Eigen::MatrixXd Jn = numericJ(t, x, i);
		EXPECT_EQ(L.J[i].rows(), Jn.rows()) << t.name() << " block " << toString(t.keys()[i]);
		EXPECT_EQ(L.J[i].cols(), Jn.cols()) << t.name() << " block " << toString(t.keys()[i]);
		if (L.J[i].rows() != Jn.rows() || L.J[i].cols() != Jn.cols()) return 1e300;
		const double e =
		    (L.J[i] - Jn).cwiseAbs().maxCoeff() / std::max(1.0, Jn.cwiseAbs().maxCoeff());
		EXPECT_LT(e, tol) << t.name() << " block " << toString(t.keys()[i]) << "\nanalytic:\n"
		                  << L.J[i] << "\nnumeric:\n"
		                  << Jn;
		worst = std::max(worst, e);
	}
	return worst;
}

/** Test headings: generic, and just below +pi / above -pi. */
const double kHeadings[] = {0.7, M_PI - 2e-7, -M_PI + 2e-7, -2.3};

Eigen::Vector2d pt(std::mt19937& g, double s = 5)
{
	std::uniform_real_distribution<double> U(-s, s);
	return Eigen::Vector2d(U(g), U(g));
}
}  // namespace

TEST(TermJacobians, Prior)
{
	const std::vector<TVarKey> keys{TVarKey::ego(0), TVarKey::landmark(3),
	                                TVarKey::objectPose(1, 2)};
	Eigen::VectorXd mean(8);
	mean << 1, 2, M_PI - 1e-3, 4, 5, 0.1, 0.2, -M_PI + 1e-3;
	Eigen::MatrixXd Om = Eigen::MatrixXd::Identity(8, 8);
	Om(0, 2) = Om(2, 0) = 0.3;
	const CPriorTerm t(keys, {3, 2, 3}, mean, Om);
	for (double th : kHeadings)
		checkTerm(t, {Eigen::Vector3d(1.1, 2.2, th), Eigen::Vector2d(4.1, 4.9),
		              Eigen::Vector3d(0.3, 0.1, -th)});
}

TEST(TermJacobians, Odometry)
{
	Eigen::Matrix3d S;
	S << 4e-4, 1e-4, 2e-5, 1e-4, 1e-4, -1e-5, 2e-5, -1e-5, 1e-5;
	const COdometryTerm t(3, 4, Eigen::Vector3d(1.0, 0.2, 0.3), S);
	for (double th : kHeadings)
		checkTerm(
		    t, {Eigen::Vector3d(1, 2, th), Eigen::Vector3d(1.9, 2.5, models::wrapToPi(th + 0.28))});
}

TEST(TermJacobians, MeasurementBothModels)
{
	std::mt19937 g(3);
	for (auto model : {models::MeasurementModel::Cartesian, models::MeasurementModel::RangeBearing})
		for (double th : kHeadings)
		{
			const Eigen::Vector3d x(1, -2, th);
			for (const TVarKey& f : {TVarKey::landmark(7), TVarKey::objectFeature(2, 1, 5)})
			{
				const Eigen::Vector2d p = x.head<2>() + pt(g);
				const Eigen::Vector2d z =
				    models::observe(model, x, p) + Eigen::Vector2d(0.01, -0.02);
				const CMeasurementTerm t(5, f, z, model, Eigen::Vector2d(1e-3, 2e-4).asDiagonal());
				checkTerm(t, {x, p});
			}
		}
}

namespace
{
/** Keys and values of an object with n time-0 features, m of them seen at t (seen = 0..m-1
 * reversed), features moved rigidly by xi plus a small misfit. */
TObjectPoseKeys objectKeys(size_t n, size_t m, const Eigen::VectorXd& xi, std::mt19937& g,
                           std::vector<Eigen::VectorXd>& x)
{
	TObjectPoseKeys k;
	k.pose = TVarKey::objectPose(1, 6);
	x = {xi};
	Eigen::Matrix2Xd f0(2, Eigen::Index(n));
	for (size_t i = 0; i < n; ++i)
	{
		k.f0.push_back(TVarKey::objectFeature(1, int32_t(i), 0));
		f0.col(Eigen::Index(i)) = Eigen::Vector2d(3, 1) + pt(g, 2);
		x.push_back(f0.col(Eigen::Index(i)));
	}
	const Eigen::Vector2d c = f0.rowwise().mean();
	const double th = xi.size() == 3 ? xi[2] : 0.0;
	for (size_t i = 0; i < m; ++i)
	{
		const int s = int(m - 1 - i);
		k.ft.push_back(TVarKey::objectFeature(1, s, 6));
		k.seen.push_back(s);
		const Eigen::Vector2d p = c + models::rot2(th) * (f0.col(s) - c) + xi.head<2>();
		x.push_back(Eigen::Vector2d(p + 0.05 * pt(g, 1)));
	}
	return k;
}
}  // namespace

TEST(TermJacobians, ObjectPoseFeatureAndPoseSpace)
{
	std::mt19937 g(5);
	const Eigen::Matrix2d Sxi = Eigen::Vector2d(0.1, 0.05).asDiagonal();
	for (double th : kHeadings)
		for (const auto& [n, m] : std::vector<std::pair<size_t, size_t>>{{3, 3}, {4, 2}, {2, 2}})
		{
			std::vector<Eigen::VectorXd> x;
			const TObjectPoseKeys k = objectKeys(n, m, Eigen::Vector3d(1.5, -0.5, th), g, x);
			SCOPED_TRACE(::testing::Message() << "n " << n << " m " << m << " heading " << th);
			checkTerm(CObjectPoseFeatureTerm(k, Sxi), x);
			checkTerm(CObjectPosePoseTerm(k, Sxi), x, 2e-6);
		}
	// One-feature objects: translation-only poses.
	std::vector<Eigen::VectorXd> x;
	const TObjectPoseKeys k = objectKeys(1, 1, Eigen::Vector2d(0.4, 0.9), g, x);
	checkTerm(CObjectPoseFeatureTerm(k, Sxi), x);
	checkTerm(CObjectPosePoseTerm(k, Sxi), x);
}

TEST(TermJacobians, Smoothing)
{
	const TVarKey a = TVarKey::objectPose(0, 1), b = TVarKey::objectPose(0, 2),
	              c = TVarKey::objectPose(0, 3);
	const Eigen::Matrix3d Ss = Eigen::Vector3d(1e-2, 2e-2, 1e-3).asDiagonal();
	for (double th : kHeadings)
		checkTerm(
		    CSmoothingTerm(a, b, c, Ss),
		    {Eigen::Vector3d(0.1, 0.2, th), Eigen::Vector3d(0.5, 0.3, models::wrapToPi(th + 0.1)),
		     Eigen::Vector3d(0.8, 0.5, models::wrapToPi(th + 0.25))});
	checkTerm(CSmoothingTerm(a, b, c, Ss.topLeftCorner(2, 2)),
	          {Eigen::Vector2d(0.1, 0.2), Eigen::Vector2d(0.5, 0.3), Eigen::Vector2d(0.8, 0.5)});
}

TEST(TermJacobians, BodyPoseMeasurement)
{
	const TVarKey body = TVarKey::objectBodyPose(2, 4);
	Eigen::Matrix3d ST;
	ST << 1e-3, 2e-4, 1e-5, 2e-4, 2e-3, 0, 1e-5, 0, 1e-4;
	for (double th : kHeadings)
	{
		const Eigen::Vector3d x(1, 2, th);
		const CBodyPoseMeasurementTerm t3(4, body, Eigen::Vector3d(3, -1, 0.2), ST);
		checkTerm(t3, {x, Eigen::Vector3d(3.5, 1.2, models::wrapToPi(-th + 0.3))});
		const CBodyPoseMeasurementTerm t2(4, body, Eigen::Vector2d(3, -1), ST.topLeftCorner(2, 2));
		checkTerm(t2, {x, Eigen::Vector2d(3.5, 1.2)});
	}
}

TEST(TermJacobians, ObjectMotionSightingAndVelocityInit)
{
	// The object-centric terms (issue 13): CV and CTRV motion (turn rate 0 and generic, object
	// rotation next to +-pi), the sighting of a feature of a 3-feature and a 1-feature object
	// from a sensor off the robot origin, both measurement models, and the velocity's
	// initialisation term.
	estimator::TCvParams p;
	p.dt = 0.5;
	const std::shared_ptr<const estimator::IObjectMotionModel> cv =
	    std::make_shared<estimator::CConstantVelocity>(p);
	const std::shared_ptr<const estimator::IObjectMotionModel> ctrv =
	    std::make_shared<estimator::CConstantTurnRate>(p);
	const TVarKey xa = TVarKey::objectPose(1, 3), va = TVarKey::objectVelocity(1, 3),
	              xb = TVarKey::objectPose(1, 4), vb = TVarKey::objectVelocity(1, 4);
	std::mt19937 g(13);
	for (const auto& model : {cv, ctrv})
		for (double th : kHeadings)
			for (double w : {0.0, 0.4})
			{
				const Eigen::Vector3d v(1.5, -0.7, w);
				Eigen::VectorXd s(6);
				s << 0.3, 0.2, th, v;
				const Eigen::VectorXd n = model->predict(s, nullptr, nullptr);
				const CObjectMotionTerm t(model, xa, va, xb, vb);
				checkTerm(t, {s.head(3), s.tail(3), n.head(3) + Eigen::Vector3d(0.01, -0.02, 0.003),
				              n.tail(3) + Eigen::Vector3d(0.02, 0.01, -0.01)});
				checkTerm(
				    CObjectMotionTerm(model, xa, va, xb, vb),
				    {s.head(2), s.segment(3, 2), Eigen::Vector2d(1, 2), Eigen::Vector2d(1, 0)});
			}
	const Eigen::Vector3d sensor(0.3, -0.1, 0.2);
	for (auto mm : {models::MeasurementModel::Cartesian, models::MeasurementModel::RangeBearing})
		for (double th : kHeadings)
		{
			const Eigen::Vector3d x(1, -2, th);
			std::vector<TVarKey> f0{TVarKey::objectFeature(1, 0, 0),
			                        TVarKey::objectFeature(1, 2, 0),
			                        TVarKey::objectFeature(1, 3, 0)};
			const Eigen::Vector2d z(4.0, 0.3);
			const Eigen::Matrix2d Sv = Eigen::Vector2d(1e-4, 2e-4).asDiagonal();
			for (int k = 0; k < 3; ++k)
				checkTerm(CObjectSightingTerm(4, xb, f0, k, z, mm, Sv, sensor),
				          {x, Eigen::Vector3d(0.5, 0.4, models::wrapToPi(-th)),
				           pt(g) + Eigen::Vector2d(6, 0), pt(g) + Eigen::Vector2d(6, 0),
				           pt(g) + Eigen::Vector2d(6, 0)});
			checkTerm(CObjectSightingTerm(4, xb, {f0[0]}, 0, z, mm, Sv, sensor),
			          {x, Eigen::Vector2d(0.5, 0.4), pt(g) + Eigen::Vector2d(6, 0)});
		}
	// The initial velocity xi / (k dt) is discontinuous where the rotation since the first
	// sighting wraps (+-pi: an object that turned half a turn has an ambiguous turn rate; the
	// EKF uses the same function): checked away from the cut.
	for (double th : {0.7, -2.3, 3.0})
		checkTerm(CObjectVelocityInitTerm(cv, xb, vb, 3, 3),
		          {Eigen::Vector3d(0.5, 0.4, th), Eigen::Vector3d(0.3, 0.1, 0.2)});
	EXPECT_THROW(
	    CObjectSightingTerm(4, xb, {TVarKey::objectFeature(1, 0, 0)}, 1, Eigen::Vector2d(1, 1),
	                        models::MeasurementModel::Cartesian, Eigen::Matrix2d::Identity()),
	    std::invalid_argument);
}

TEST(TermJacobians, ObjectMixtureMotion)
{
	// object_model = mm (issue 28): the moment-matched mixture of a cv and a ctrv prediction
	// made at s_lin (models::mixModes, as estimator::CObjectModes does), checked at s_lin and
	// away from it, rotations next to +-pi. The residual is affine in every block (up to the
	// wrap of the heading rows, which numericJ wraps too), so central differences have no
	// truncation error: what is left is rounding, eps |r| / h ~ 1e-10 for |r| ~ 10 at h = 1e-6,
	// well inside the default 1e-6; a wrong sign or column of F_bar is an error of order
	// |F_bar| >= 1.
	estimator::TCvParams p;
	p.dt = 0.5;
	const estimator::CConstantVelocity cv(p);
	const estimator::CConstantTurnRate ctrv(p);
	const TVarKey xa = TVarKey::objectPose(1, 3), va = TVarKey::objectVelocity(1, 3),
	              xb = TVarKey::objectPose(1, 4), vb = TVarKey::objectVelocity(1, 4);
	std::mt19937 g(17);
	for (double th : kHeadings)
	{
		Eigen::VectorXd s(6);
		s << 0.3, 0.2, th, 1.5, -0.7, 0.4;
		std::vector<Eigen::VectorXd> sj;
		std::vector<Eigen::MatrixXd> Fj, Qj;
		const estimator::IObjectMotionModel* const modes[] = {&cv, &ctrv};
		for (const estimator::IObjectMotionModel* m : modes)
		{
			Eigen::MatrixXd F, Q;
			sj.push_back(m->predict(s, &F, &Q));
			Fj.push_back(F);
			Qj.push_back(Q);
		}
		Eigen::MatrixXd P = Eigen::MatrixXd::Identity(6, 6) * 0.05;
		P(0, 3) = P(3, 0) = 0.01;
		const models::TModeMixture mix =
		    models::mixModes(sj, Fj, Qj, Eigen::Vector2d(0.7, 0.3), P, 2);
		const CObjectMixtureMotionTerm t(xa, va, xb, vb, s, mix);
		SCOPED_TRACE(::testing::Message() << "heading " << th);
		// At s_lin, next to the mixture's mean.
		checkTerm(t, {s.head(3), s.tail(3), mix.s.head(3) + Eigen::Vector3d(0.01, -0.02, 0.003),
		              mix.s.tail(3) + Eigen::Vector3d(0.02, 0.01, -0.01)});
		// Away from s_lin (the previous pose across the cut for the headings next to it).
		const Eigen::Vector2d a = 0.2 * pt(g, 1), b = 0.1 * pt(g, 1);
		const Eigen::Vector3d dxi(a[0], a[1], 3e-7), dv(b[0], b[1], 0.05);
		checkTerm(t, {blockPlus(VarKind::ObjectPose, s.head(3), dxi), s.tail(3) + dv,
		              blockPlus(VarKind::ObjectPose, mix.s.head(3), -dxi), mix.s.tail(3)});
	}
}

TEST(TermJacobians, ObjectMixtureMotionSizes)
{
	// The constructor's checks: s_bar, F_bar and s_lin of one size (each off by one throws),
	// Q_eff positive definite; the matching sizes construct.
	const TVarKey xa = TVarKey::objectPose(1, 3), va = TVarKey::objectVelocity(1, 3),
	              xb = TVarKey::objectPose(1, 4), vb = TVarKey::objectVelocity(1, 4);
	models::TModeMixture mix;
	mix.s = Eigen::VectorXd::Zero(6);
	mix.F = Eigen::MatrixXd::Identity(6, 6);
	mix.Q_eff = Eigen::MatrixXd::Identity(6, 6) * 1e-2;
	const Eigen::VectorXd sLin = Eigen::VectorXd::Zero(6);
	EXPECT_NO_THROW(CObjectMixtureMotionTerm(xa, va, xb, vb, sLin, mix));
	EXPECT_THROW(CObjectMixtureMotionTerm(xa, va, xb, vb, Eigen::VectorXd::Zero(5), mix),
	             std::invalid_argument);
	models::TModeMixture bad = mix;
	bad.s = Eigen::VectorXd::Zero(7);
	EXPECT_THROW(CObjectMixtureMotionTerm(xa, va, xb, vb, sLin, bad), std::invalid_argument);
	bad = mix;
	bad.F = Eigen::MatrixXd::Identity(5, 6);
	EXPECT_THROW(CObjectMixtureMotionTerm(xa, va, xb, vb, sLin, bad), std::invalid_argument);
	bad = mix;
	bad.F = Eigen::MatrixXd::Identity(6, 5);
	EXPECT_THROW(CObjectMixtureMotionTerm(xa, va, xb, vb, sLin, bad), std::invalid_argument);
	bad = mix;
	bad.Q_eff(2, 2) = 0;  // semidefinite: the framework needs an invertible process noise
	EXPECT_THROW(CObjectMixtureMotionTerm(xa, va, xb, vb, sLin, bad), std::invalid_argument);
	// linearize's own check: blocks that do not add up to s_lin.
	const CObjectMixtureMotionTerm t(xa, va, xb, vb, sLin, mix);
	EXPECT_THROW(t.linearize({Eigen::Vector2d::Zero(), Eigen::Vector3d::Zero(),
	                          Eigen::Vector2d::Zero(), Eigen::Vector3d::Zero()}),
	             std::invalid_argument);
}
