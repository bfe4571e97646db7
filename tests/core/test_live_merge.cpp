/** The velocity residual of the live-merge test (models/live_merge.h, classify_merge_live,
 * doc/results/classification.md "Merging two live objects"): zero for a point carried by A's twist
 * (the rigid flow differentiated numerically, independent of the formula), and J_out_in against
 * central differences at random states and at headings +-pi, for B with 2 and 3 pose entries. */
#include <dynslam/core/models/live_merge.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam;
using core_test::unvec;
using core_test::vec;

namespace
{
struct TCase
{
	Eigen::Vector3d xiA, vA;
	Eigen::Matrix2Xd f0A, f0B;
	Eigen::VectorXd xiB, vB;
	Eigen::VectorXd input() const
	{
		Eigen::VectorXd v(3 + f0A.size() + 3 + xiB.size() + f0B.size() + vB.size());
		v << xiA, vec(f0A), vA, xiB, vec(f0B), vB;
		return v;
	}
	Eigen::VectorXd at(const Eigen::VectorXd& v) const
	{
		Eigen::Index o = 0;
		const auto take = [&](Eigen::Index n)
		{
			const Eigen::VectorXd s = v.segment(o, n);
			o += n;
			return s;
		};
		const Eigen::Vector3d a = take(3);
		const Eigen::Matrix2Xd fa = unvec(take(f0A.size()));
		const Eigen::Vector3d va = take(3);
		const Eigen::VectorXd b = take(xiB.size());
		const Eigen::Matrix2Xd fb = unvec(take(f0B.size()));
		const Eigen::VectorXd vb = take(vB.size());
		return models::rigidVelocityResidual(a, fa, va, b, fb, vb);
	}
};

TCase randomCase(int dB, int nA, int nB, double headingA, double headingB)
{
	TCase c;
	c.xiA = core_test::randomVector(3, -20, 20);
	c.xiA[2] = headingA;
	c.vA = core_test::randomVector(3, -5, 5);
	c.f0A = core_test::randomObject(nA);
	c.f0B = core_test::randomObject(nB);
	c.xiB = core_test::randomVector(dB, -20, 20);
	if (dB == 3) c.xiB[2] = headingB;
	c.vB = core_test::randomVector(dB, -5, 5);
	return c;
}
}  // namespace

TEST(LiveMerge, PointCarriedByTheTwistOfAHasZeroResidual)
{
	dynslam_test::rng(21);
	for (int trial = 0; trial < 20; ++trial)
	{
		TCase c = randomCase(3, 3, 2, core_test::randomPose()[2], 0.3);
		const Eigen::Vector2d pA = c.f0A.rowwise().mean() + c.xiA.head<2>();
		const Eigen::Vector2d pB = c.f0B.rowwise().mean() + c.xiB.head<2>();
		// The rigid flow of A: after time h its reference point is at pA + vA h and every point
		// has turned by omega h about it; B's reference point's velocity by central difference.
		const auto flow = [&](double h) {
			return Eigen::Vector2d(pA + c.vA.head<2>() * h + models::rot2(c.vA[2] * h) * (pB - pA));
		};
		const double h = 1e-6;
		const Eigen::Vector2d vB = (flow(h) - flow(-h)) / (2 * h);
		c.vB << vB, c.vA[2];
		EXPECT_LT(c.at(c.input()).norm(), 1e-6) << "trial " << trial;
		// Another velocity is not rigid.
		c.vB[0] += 0.1;
		EXPECT_NEAR(c.at(c.input()).norm(), 0.1, 1e-6);
	}
}

TEST(LiveMerge, VelocityResidualJacobian)
{
	dynslam_test::rng(22);
	double worst = 0;
	std::vector<double> headings = core_test::wrapHeadings();
	for (int k = 0; k < 6; ++k) headings.push_back(core_test::randomPose()[2]);
	for (const int dB : {2, 3})
		for (const int nA : {1, 2, 4})
			for (const double hd : headings)
			{
				const TCase c = randomCase(dB, nA, dB == 2 ? 1 : 3, hd, -hd);
				Eigen::MatrixXd J;
				const Eigen::VectorXd r =
				    models::rigidVelocityResidual(c.xiA, c.f0A, c.vA, c.xiB, c.f0B, c.vB, &J);
				EXPECT_EQ(r.size(), dB);
				const core_test::VecFn f = [&c](const Eigen::VectorXd& v) { return c.at(v); };
				EXPECT_TRUE(core_test::checkJacobian(J, f, c.input(), {}, worst))
				    << "dB " << dB << " nA " << nA << " heading " << hd;
			}
	core_test::reportWorst("rigidVelocityResidual J_out_in", worst);
}

TEST(LiveMerge, BadSizesThrow)
{
	const Eigen::Matrix2Xd one = Eigen::Matrix2Xd::Zero(2, 1), two = Eigen::Matrix2Xd::Zero(2, 2);
	const Eigen::Vector3d z3 = Eigen::Vector3d::Zero();
	EXPECT_THROW(models::rigidVelocityResidual(z3, Eigen::Matrix2Xd(2, 0), z3, z3, one, z3),
	             std::invalid_argument);
	EXPECT_THROW(models::rigidVelocityResidual(z3, one, z3, Eigen::Vector2d::Zero(), two,
	                                           Eigen::Vector2d::Zero()),
	             std::invalid_argument);
	EXPECT_THROW(models::rigidVelocityResidual(z3, one, z3, z3, one, Eigen::Vector2d::Zero()),
	             std::invalid_argument);
}
