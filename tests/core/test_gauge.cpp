/** The prior gauge (models/gauge.h, issue 13): the Jacobian N of every block type against
 * central differences of the transform (random values, headings at +-pi), the invariance of
 * the object readings under the transform (what makes the anchored filter exact in the linear
 * case), the commutation of the cv / ctrv predictions with it, and P + N Sigma_0 N^T against a
 * dense entry-by-entry sum. */
#include <dynslam/core/models/gauge.h>
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam::models;
using core_test::checkJacobian;
using dynslam_test::uniform;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
struct TCase
{
	GaugeKind kind;
	int dim;
	std::vector<int> angles;  ///< angle entries of the block
};
const std::vector<TCase> kCases{{GaugeKind::EgoPose, 3, {2}},  {GaugeKind::Point, 2, {}},
                                {GaugeKind::Vector, 2, {}},    {GaugeKind::RelPose, 3, {2}},
                                {GaugeKind::Velocity3, 3, {}}, {GaugeKind::Invariant, 2, {}}};

/** Block values: random, then with the angle entry at the wrap. */
std::vector<VectorXd> values(const TCase& c)
{
	std::vector<VectorXd> v;
	for (int i = 0; i < 30; ++i) v.push_back(core_test::randomVector(c.dim, -40, 40));
	for (const double th : core_test::wrapHeadings())
		for (VectorXd x : {core_test::randomVector(c.dim, -40, 40)})
		{
			for (int a : c.angles) x[a] = th;
			v.push_back(x);
		}
	for (auto& x : v)
		for (int a : c.angles) x[a] = wrapToPi(x[a]);
	return v;
}
}  // namespace

TEST(Gauge, JacobianOfEveryBlockKindVsCentralDifferences)
{
	dynslam_test::rng(1313);
	double worst = 0;
	for (const TCase& c : kCases)
		for (const VectorXd& x : values(c))
		{
			const Eigen::Vector2d p0 = core_test::randomVector(2, -20, 20);
			const MatrixXd J = J_block_delta(c.kind, x, p0);
			const core_test::VecFn f = [&](const VectorXd& d)
			{ return gaugeTransform(c.kind, x, d, p0); };
			EXPECT_TRUE(checkJacobian(J, f, VectorXd::Zero(3), c.angles, worst))
			    << "kind " << int(c.kind);
			// The transform at delta = 0 is the identity.
			EXPECT_LT((gaugeTransform(c.kind, x, Eigen::Vector3d::Zero(), p0) - x).norm(), 1e-12);
		}
	core_test::reportWorst("gauge N vs central differences", worst);
}

TEST(Gauge, ObjectReadingsAreInvariantUnderTheTransform)
{
	dynslam_test::rng(1314);
	double worst = 0;
	for (const MeasurementModel m : {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (const int d : {2, 3})
			for (int trial = 0; trial < 40; ++trial)
			{
				const Eigen::Vector3d x = core_test::randomPose();
				VectorXd xi = core_test::randomVector(d, -10, 10);
				if (d == 3)
					xi[2] = trial < 4 ? core_test::wrapHeadings()[size_t(trial) % 2]
					                  : uniform(-M_PI, M_PI);
				const int n = d == 3 ? 3 : 1;
				Eigen::Matrix2Xd f0(2, n);
				for (int k = 0; k < n; ++k) f0.col(k) = core_test::randomVector(2, -40, 40);
				const Eigen::Vector3d delta(uniform(-5, 5), uniform(-5, 5), uniform(-M_PI, M_PI));
				const Eigen::Vector2d p0 = core_test::randomVector(2, -20, 20);
				const VectorXd x2 = gaugeTransform(GaugeKind::EgoPose, x, delta, p0);
				const VectorXd xi2 =
				    gaugeTransform(d == 3 ? GaugeKind::RelPose : GaugeKind::Vector, xi, delta, p0);
				Eigen::Matrix2Xd f02(2, n);
				for (int k = 0; k < n; ++k)
					f02.col(k) = gaugeTransform(GaugeKind::Point, f0.col(k), delta, p0);
				for (int k = 0; k < n; ++k)
				{
					const Eigen::Vector2d z = observeObjectFeature(m, x, xi, f0, k);
					const Eigen::Vector2d z2 = observeObjectFeature(m, x2, xi2, f02, k);
					Eigen::Vector2d e = z2 - z;
					if (m == MeasurementModel::RangeBearing) e[1] = wrapToPi(e[1]);
					worst = std::max(worst, e.norm());
				}
			}
	EXPECT_LT(worst, 1e-9);
	core_test::reportWorst("object reading change under the transform", worst);
}

TEST(Gauge, ObjectPredictionsCommuteWithTheTransform)
{
	dynslam_test::rng(1315);
	double worst = 0;
	for (const bool ctrv : {false, true})
		for (const int d : {2, 3})
			for (int trial = 0; trial < 40; ++trial)
			{
				VectorXd s = core_test::randomVector(2 * d, -5, 5);
				if (d == 3) s[2] = trial < 2 ? core_test::wrapHeadings()[size_t(trial)] : s[2];
				const Eigen::Vector3d delta(uniform(-5, 5), uniform(-5, 5), uniform(-M_PI, M_PI));
				const Eigen::Vector2d p0 = core_test::randomVector(2, -20, 20);
				auto transform = [&](const VectorXd& st)
				{
					VectorXd out = st;
					out.head(d) = gaugeTransform(d == 3 ? GaugeKind::RelPose : GaugeKind::Vector,
					                             st.head(d), delta, p0);
					out.tail(d) = gaugeTransform(d == 3 ? GaugeKind::Velocity3 : GaugeKind::Vector,
					                             st.tail(d), delta, p0);
					return out;
				};
				auto predict = [&](const VectorXd& st)
				{ return ctrv ? ctrvPredict(st, 0.5) : cvPredict(st, 0.5); };
				VectorXd e = predict(transform(s)) - transform(predict(s));
				if (d == 3) e[2] = wrapToPi(e[2]);
				worst = std::max(worst, e.norm());
			}
	EXPECT_LT(worst, 1e-9);
	core_test::reportWorst("prediction commutation error", worst);
}

TEST(Gauge, OutputTermEqualsADenseSum)
{
	dynslam_test::rng(1316);
	const int n = 9;
	const MatrixXd A = core_test::randomVector(n * n, -1, 1).reshaped(n, n);
	const MatrixXd P = A * A.transpose();
	const MatrixXd N = core_test::randomVector(n * 3, -3, 3).reshaped(n, 3);
	const Eigen::Matrix3d S = Eigen::Vector3d(1e-4, 2e-4, 1e-6).asDiagonal();
	const MatrixXd R = addGaugeTerm(P, N, S);
	double worst = 0;
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
		{
			double v = P(i, j);
			for (int a = 0; a < 3; ++a)
				for (int b = 0; b < 3; ++b) v += N(i, a) * S(a, b) * N(j, b);
			worst = std::max(worst, std::abs(R(i, j) - v));
		}
	EXPECT_LT(worst, 1e-14);
	EXPECT_THROW(addGaugeTerm(P, N.topRows(3), S), std::invalid_argument);
	EXPECT_THROW(J_block_delta(GaugeKind::EgoPose, VectorXd::Zero(2), Eigen::Vector2d::Zero()),
	             std::invalid_argument);
}
