/** objectPoseAugmentations is the arithmetic of before, bit for bit: its workspaces (the rows of
 * the extended covariance in a reused row-major buffer, the products in reused temporaries,
 * doc/performance.md section 16) change where the numbers are stored, not how they are
 * computed. The reference below is the code of before (2026-11-24, 4d20605), copied. */
#include <dynslam/ekf_steps.h>
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

bool same(const MatrixXd& A, const MatrixXd& B)
{
	return A.rows() == B.rows() && A.cols() == B.cols() && (A.array() == B.array()).all();
}
}  // namespace

// Highway-like sizes: ~120 existing entries, pending features, objects of 1, 3 and 5 features
// (their time-t features partly among the pending ones), called twice with other sizes so the
// reused buffers shrink and grow.
TEST(PoseAugmentationExact, EqualsTheCodeOfBeforeBitForBit)
{
	dynslam_test::rng(1601);
	for (const auto& [n, m] : std::vector<std::pair<int, int>>{{121, 10}, {37, 0}, {203, 24}})
	{
		const RowMatrixXd P = core_test::randomSPD(n, 0.5);
		VectorXd x(n + m);
		x << core_test::randomPose(), core_test::randomVector(n + m - 3, -30, 30);
		ekf::Augmentation a;
		a.mean = x.tail(m);
		a.cross = core_test::randomSPD(n + m, 0.3).bottomLeftCorner(m, n);
		a.cov = core_test::randomSPD(m, 0.4);
		const Eigen::Matrix2d Sxi = Eigen::Matrix2d::Identity() * 0.01;
		// rigid objects: f0 at 3.., ft near the end (pending ones when m > 0); one 1-feature object
		std::vector<ekf::ObjectPoseLinearization> lins = {
		    ekf::linearizeObjectPose(x, {5, 7, 9}, {n + m - 6, n + m - 4, n + m - 2}, {}, Sxi),
		    ekf::linearizeObjectPose(x, {11}, {13}, {}, Sxi),
		    ekf::linearizeObjectPose(x, {15, 17, 19, 21, 23}, {25, 27, 29, 31, 33}, {}, Sxi)};
		const std::vector<Eigen::Index> at{0, 4, 6};
		const Eigen::Index size = 10;
		const ekf::Augmentation b = poseAugmentationsBefore(P, a, lins, at, size);
		const ekf::Augmentation c = ekf::objectPoseAugmentations(P, a, lins, at, size);
		EXPECT_TRUE(same(c.mean, b.mean)) << "n = " << n;
		EXPECT_TRUE(same(c.cross, b.cross)) << "n = " << n;
		EXPECT_TRUE(same(c.cov, b.cov)) << "n = " << n;
		EXPECT_TRUE(
		    same(ekf::extendedRows(P, a, lins[2].idx), extendedRowsBefore(P, a, lins[2].idx)));
	}
}
