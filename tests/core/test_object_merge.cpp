/** Merging an object N into an object L (models/object_merge.h, classify_merge_linked,
 * doc/results/classification.md "Merging a linked object"): N's features re-expressed in L's body
 * frame are where N put them (g_L(xi_L, f') = g_N(xi_N, f^N), L's centroid fixed by its founders),
 * and the Jacobian J_out_in against central differences, at random states and at headings +-pi, for
 * every pose dimension (L: 2 or 3 entries; N: none, 2 or 3). */
#include <dynslam/core/models/object_merge.h>
#include <dynslam/core/models/object_pose.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam;
using core_test::unvec;
using core_test::vec;

namespace
{
struct TCase
{
	Eigen::VectorXd xiL, xiN;
	Eigen::Matrix2Xd f0L, fN;
	int foundersN = 0;
	/** The input vector [xi_L; vec(f0L); xi_N; vec(fN)]. */
	Eigen::VectorXd input() const
	{
		Eigen::VectorXd v(xiL.size() + f0L.size() + xiN.size() + fN.size());
		v << xiL, vec(f0L), xiN, vec(fN);
		return v;
	}
	/** g evaluated at input v (laid out as input()). */
	Eigen::VectorXd at(const Eigen::VectorXd& v) const
	{
		Eigen::Index o = 0;
		const auto take = [&](Eigen::Index n)
		{
			const Eigen::VectorXd s = v.segment(o, n);
			o += n;
			return s;
		};
		const Eigen::VectorXd a = take(xiL.size());
		const Eigen::Matrix2Xd b = unvec(take(f0L.size()));
		const Eigen::VectorXd c = take(xiN.size());
		const Eigen::Matrix2Xd d = unvec(take(fN.size()));
		return vec(models::mergeObjectFeatures(a, b, c, d, foundersN));
	}
};

Eigen::VectorXd pose(int d, double heading)
{
	Eigen::VectorXd p = core_test::randomVector(d, -20, 20);
	if (d == 3) p[2] = heading;
	return p;
}

/** World position of N's features: g_N(xi_N, f^N). */
Eigen::Matrix2Xd worldOfN(const TCase& c)
{
	if (c.xiN.size() == 0) return c.fN;
	if (c.xiN.size() == 2) return c.fN.colwise() + Eigen::Vector2d(c.xiN);
	return models::objectPoseMap(Eigen::Vector3d(c.xiN), c.fN, nullptr, nullptr, c.foundersN);
}

/** Where L puts its features: g_L(xi_L, f') with L's founders' centroid. */
Eigen::Matrix2Xd worldOfL(const TCase& c, const Eigen::Matrix2Xd& f)
{
	if (c.xiL.size() == 2) return f.colwise() + Eigen::Vector2d(c.xiL);
	Eigen::Matrix2Xd all(2, c.f0L.cols() + f.cols());
	all << c.f0L, f;
	return models::objectPoseMap(Eigen::Vector3d(c.xiL), all, nullptr, nullptr, int(c.f0L.cols()))
	    .rightCols(f.cols());
}
}  // namespace

TEST(ObjectMerge, FeaturesKeepTheirWorldPositionAndJacobian)
{
	dynslam_test::rng(20261125);
	double worstJ = 0, worstW = 0;
	std::vector<double> headings = core_test::wrapHeadings();
	for (int i = 0; i < 6; ++i) headings.push_back(core_test::randomPose()[2]);
	for (const int dL : {2, 3})
		for (const int dN : {0, 2, 3})
			for (const double h : headings)
			{
				TCase c;
				c.xiL = pose(dL, h);
				c.xiN = pose(dN, -h);
				c.f0L = core_test::randomObject(3);
				c.fN = core_test::randomObject(4);
				c.foundersN = 3;  // N's last feature joined it later: not in its centroid
				Eigen::MatrixXd J;
				const Eigen::Matrix2Xd f =
				    models::mergeObjectFeatures(c.xiL, c.f0L, c.xiN, c.fN, c.foundersN, &J);
				const double w = (worldOfL(c, f) - worldOfN(c)).cwiseAbs().maxCoeff();
				worstW = std::max(worstW, w);
				EXPECT_LT(w, 1e-11) << "dL " << dL << " dN " << dN << " heading " << h;
				EXPECT_TRUE(core_test::checkJacobian(
				    J, [&](const Eigen::VectorXd& v) { return c.at(v); }, c.input(), {}, worstJ))
				    << "dL " << dL << " dN " << dN << " heading " << h;
			}
	core_test::reportWorst("merge Jacobian relative error", worstJ);
	core_test::reportWorst("merge world position error [m]", worstW);
}

TEST(ObjectMerge, TranslationOnlyLAndBadSizes)
{
	// L translation-only (one founder): f' = g_N(...) - xi_L, no founders needed.
	const Eigen::Matrix2Xd fN = (Eigen::Matrix2Xd(2, 2) << 1, 2, 3, 4).finished();
	const Eigen::Matrix2Xd f = models::mergeObjectFeatures(
	    Eigen::Vector2d(0.5, -1), Eigen::Matrix2Xd(2, 0), Eigen::VectorXd(), fN, 2);
	EXPECT_EQ(f, (Eigen::Matrix2Xd(2, 2) << 0.5, 1.5, 4, 5).finished());
	const Eigen::Matrix2Xd none(2, 0);
	EXPECT_THROW(
	    models::mergeObjectFeatures(Eigen::Vector3d(1, 2, 3), none, Eigen::VectorXd(), fN, 2),
	    std::invalid_argument);  // a 3-dof L without founders
	EXPECT_THROW(
	    models::mergeObjectFeatures(Eigen::Vector2d(1, 2), none, Eigen::Vector3d(1, 2, 3), fN, 3),
	    std::invalid_argument);  // foundersN > m
	EXPECT_THROW(models::mergeObjectFeatures(Eigen::VectorXd(4), none, Eigen::VectorXd(), fN, 2),
	             std::invalid_argument);
}
