/** objectPoseAugmentations with the portable kernels is the arithmetic of before, bit for bit:
 * its workspaces (the rows of the extended covariance in a reused row-major buffer, the products
 * in reused temporaries, doc/results/performance.md section 16) change where the numbers are
 * stored, not how they are computed. The reference below is the code of before (2026-11-24,
 * 4d20605), copied. With the AVX2 kernels Gamma * rows (kernels::productColRow) differs in the last
 * bits: measured here against the portable variant, within 1e-12 relative. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/kernels.h>
#include <gtest/gtest.h>

#include "core_test_utils.h"

using namespace dynslam;
using dynslam::ekf::RowMatrixXd;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
MatrixXd extendedRowsBefore(const RowMatrixXd& P, const ekf::Augmentation& a,
                            const std::vector<int>& idx)
{
	const Eigen::Index n = P.rows(), m = a.mean.size();
	MatrixXd rows(idx.size(), n + m);
	for (size_t r = 0; r < idx.size(); ++r)
	{
		const Eigen::Index i = idx[r];
		if (i < n)
		{
			rows.row(r).head(n) = P.row(i);
			rows.row(r).tail(m) = a.cross.col(i).transpose();
		}
		else
		{
			rows.row(r).head(n) = a.cross.row(i - n);
			rows.row(r).tail(m) = a.cov.row(i - n);
		}
	}
	return rows;
}

ekf::Augmentation poseAugmentationsBefore(const RowMatrixXd& P, const ekf::Augmentation& a,
                                          const std::vector<ekf::ObjectPoseLinearization>& poses,
                                          const std::vector<Eigen::Index>& at, Eigen::Index size)
{
	const Eigen::Index N = P.rows() + a.mean.size();
	ekf::Augmentation out;
	out.mean = VectorXd::Zero(size);
	out.cross = MatrixXd::Zero(size, N);
	out.cov = MatrixXd::Identity(size, size);
	for (size_t o = 0; o < poses.size(); ++o)
	{
		const auto& lin = poses[o];
		const Eigen::Index d = lin.xi.size(), r = at[o];
		const MatrixXd rows = extendedRowsBefore(P, a, lin.idx);
		out.mean.segment(r, d) = lin.xi;
		MatrixXd GammaRows;
		GammaRows.noalias() = lin.Gamma * rows;
		out.cross.middleRows(r, d) = GammaRows;
		MatrixXd c = lin.Gamma * rows(Eigen::all, lin.idx) * lin.Gamma.transpose();
		c += lin.noise;
		out.cov.block(r, r, d, d) = 0.5 * (c + c.transpose());
		for (size_t q = 0; q < o; ++q)
		{
			const Eigen::Index dq = poses[q].xi.size();
			out.cov.block(r, at[q], d, dq).noalias() =
			    out.cross.middleRows(r, d)(Eigen::all, poses[q].idx) * poses[q].Gamma.transpose();
			out.cov.block(at[q], r, dq, d) = out.cov.block(r, at[q], d, dq).transpose();
		}
	}
	return out;
}

struct TPoseCase
{
	RowMatrixXd P;
	ekf::Augmentation a;
	std::vector<ekf::ObjectPoseLinearization> lins;
};

// Highway-like sizes: n existing entries, m pending features, objects of 3, 1 and 5 features
// (the first one's time-t features among the pending ones when m > 0).
TPoseCase poseCase(int n, int m)
{
	TPoseCase c;
	c.P = core_test::randomSPD(n, 0.5);
	VectorXd x(n + m);
	x << core_test::randomPose(), core_test::randomVector(n + m - 3, -30, 30);
	c.a.mean = x.tail(m);
	c.a.cross = core_test::randomSPD(n + m, 0.3).bottomLeftCorner(m, n);
	c.a.cov = core_test::randomSPD(m, 0.4);
	const Eigen::Matrix2d Sxi = Eigen::Matrix2d::Identity() * 0.01;
	c.lins = {ekf::linearizeObjectPose(x, {5, 7, 9}, {n + m - 6, n + m - 4, n + m - 2}, {}, Sxi),
	          ekf::linearizeObjectPose(x, {11}, {13}, {}, Sxi),
	          ekf::linearizeObjectPose(x, {15, 17, 19, 21, 23}, {25, 27, 29, 31, 33}, {}, Sxi)};
	return c;
}
const std::vector<Eigen::Index> kAt{0, 4, 6};
constexpr Eigen::Index kSize = 10;
const std::vector<std::pair<int, int>> kSizes{{121, 10}, {37, 0}, {203, 24}};

bool same(const MatrixXd& A, const MatrixXd& B)
{
	return A.rows() == B.rows() && A.cols() == B.cols() && (A.array() == B.array()).all();
}
}  // namespace

// Called with several sizes in turn, so the reused buffers shrink and grow.
TEST(PoseAugmentationExact, EqualsTheCodeOfBeforeBitForBit)
{
	const kernels::CScopedIsa portable(kernels::Isa::Sse2);
	dynslam_test::rng(1601);
	for (const auto& [n, m] : kSizes)
	{
		const TPoseCase c = poseCase(n, m);
		const ekf::Augmentation b = poseAugmentationsBefore(c.P, c.a, c.lins, kAt, kSize);
		const ekf::Augmentation o = ekf::objectPoseAugmentations(c.P, c.a, c.lins, kAt, kSize);
		EXPECT_TRUE(same(o.mean, b.mean)) << "n = " << n;
		EXPECT_TRUE(same(o.cross, b.cross)) << "n = " << n;
		EXPECT_TRUE(same(o.cov, b.cov)) << "n = " << n;
		EXPECT_TRUE(same(ekf::extendedRows(c.P, c.a, c.lins[2].idx),
		                 extendedRowsBefore(c.P, c.a, c.lins[2].idx)));
	}
}

// max |avx2 - sse2| / max |sse2| (the measure of doc/results/performance.md section 10).
TEST(PoseAugmentationExact, Avx2EqualsPortableWithin1e12)
{
	if (!kernels::isaAvailable(kernels::Isa::Avx2))
		GTEST_SKIP() << "AVX2/FMA variant not available";
	dynslam_test::rng(1602);
	double worst = 0;
	for (const auto& [n, m] : kSizes)
	{
		const TPoseCase c = poseCase(n, m);
		ekf::Augmentation s, v;
		{
			const kernels::CScopedIsa isa(kernels::Isa::Sse2);
			s = ekf::objectPoseAugmentations(c.P, c.a, c.lins, kAt, kSize);
		}
		{
			const kernels::CScopedIsa isa(kernels::Isa::Avx2);
			v = ekf::objectPoseAugmentations(c.P, c.a, c.lins, kAt, kSize);
		}
		for (const auto& [x, y] : {std::pair(&v.cross, &s.cross), std::pair(&v.cov, &s.cov)})
			worst = std::max(worst, (*x - *y).cwiseAbs().maxCoeff() / y->cwiseAbs().maxCoeff());
		EXPECT_TRUE(same(v.mean, s.mean));
	}
	EXPECT_LE(worst, 1e-12);
	RecordProperty("worst_relative_difference", std::to_string(worst));
	std::printf("objectPoseAugmentations avx2 vs sse2: max rel diff %.3g\n", worst);
}
