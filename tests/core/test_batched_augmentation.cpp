/** The batched augmentation of ekf_steps.h (extendedRows, objectPoseAugmentations,
 * assembleExtended), which lets CDynamicKFSLAM2D rewrite the
 * covariance once per step, vs the same step done one augmentation at a time on dense
 * matrices: new features (Alg. 3), then the poses of two objects (Alg. 4, one rigid with a
 * pad, one translation-only) each appended before the next is computed, then drops. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "core_test_utils.h"

using namespace dynslam;
using dynslam::ekf::RowMatrixXd;
using dynslam::models::MeasurementModel;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace
{
/** Appends an augmentation densely: [x; a.mean], [[P, a.cross^T], [a.cross, a.cov]]. */
void appendDense(VectorXd& x, RowMatrixXd& P, const ekf::Augmentation& a)
{
	const Eigen::Index n = x.size(), m = a.mean.size();
	VectorXd x2(n + m);
	x2 << x, a.mean;
	RowMatrixXd P2(n + m, n + m);
	P2 << P, a.cross.transpose(), a.cross, a.cov;
	x.swap(x2);
	P.swap(P2);
}

/** Appends one independent pad (mean 0, variance 1). */
void appendPad(VectorXd& x, RowMatrixXd& P)
{
	ekf::Augmentation pad;
	pad.mean = VectorXd::Zero(1);
	pad.cross = MatrixXd::Zero(1, x.size());
	pad.cov = MatrixXd::Identity(1, 1);
	appendDense(x, P, pad);
}

double relErr(const MatrixXd& A, const MatrixXd& B)
{
	EXPECT_EQ(A.rows(), B.rows());
	EXPECT_EQ(A.cols(), B.cols());
	if (A.rows() != B.rows() || A.cols() != B.cols()) return 1e300;
	return (A - B).cwiseAbs().maxCoeff() / std::max(1.0, B.cwiseAbs().maxCoeff());
}

// State: ego (0-2), static landmark (3-4), object A at time 0 (5-10, 3 features),
// object B at time 0 (11-12, 1 feature).
constexpr int kN = 13;
}  // namespace

TEST(BatchedAugmentation, EqualsSequentialDenseAugmentation)
{
	dynslam_test::rng(913);
	double worst = 0;
	for (const MeasurementModel model :
	     {MeasurementModel::Cartesian, MeasurementModel::RangeBearing})
		for (int trial = 0; trial < 20; ++trial)
		{
			const Eigen::Vector3d ego = core_test::randomPose();
			const Eigen::Matrix2Xd A0 = core_test::randomObject(3), B0 = core_test::randomObject(1);
			VectorXd x(kN);
			x << ego, core_test::randomVector(2, -40, 40), core_test::vec(A0), core_test::vec(B0);
			const RowMatrixXd P = core_test::randomSPD(kN, 0.1);
			// Time t: A moved rigidly (features 2 and 0 seen), B translated; one new landmark.
			const Eigen::Vector3d xi = core_test::randomPose();
			const Eigen::Matrix2d Rot = Eigen::Rotation2Dd(xi[2]).toRotationMatrix();
			std::vector<Eigen::Vector2d> pts = {
			    core_test::randomVector(2, -40, 40), Rot * A0.col(2) + xi.head<2>(),
			    Rot * A0.col(0) + xi.head<2>(), B0.col(0) + xi.head<2>()};
			std::vector<Eigen::Vector2d> z;
			for (const auto& p : pts) z.push_back(models::observe(model, ego, p));
			const Eigen::Matrix2d R = core_test::randomSPD(2, 1e-3);
			const Eigen::Matrix2d Sxi = core_test::randomSPD(2, 1e-2);
			const ekf::Augmentation feats =
			    ekf::featureAugmentation(model, ego, P.topRows(3), z, R);
			// new entries: landmark kN, A's features kN + 2, kN + 4, B's kN + 6
			const std::vector<int> f0A{5, 7, 9}, ftA{kN + 2, kN + 4}, seenA{2, 0}, f0B{11},
			    ftB{kN + 6};

			// Reference: one augmentation at a time, dense.
			VectorXd xd = x;
			RowMatrixXd Pd = P;
			appendDense(xd, Pd, feats);
			appendDense(xd, Pd, ekf::objectPoseAugmentation(xd, Pd, f0A, ftA, seenA, Sxi));
			appendPad(xd, Pd);
			appendDense(xd, Pd, ekf::objectPoseAugmentation(xd, Pd, f0B, ftB, {}, Sxi));
			// Drops: the static landmark (old) and the time-t features (new).
			const std::vector<int> keep = ekf::keptIndices(
			    int(xd.size()), {3, 4, kN + 2, kN + 3, kN + 4, kN + 5, kN + 6, kN + 7});

			// Batched: poses on the extended state (padded), assembled once.
			VectorXd xe(kN + feats.mean.size());
			xe << x, feats.mean;
			const std::vector<ekf::ObjectPoseLinearization> lins = {
			    ekf::linearizeObjectPose(xe, f0A, ftA, seenA, Sxi),
			    ekf::linearizeObjectPose(xe, f0B, ftB, {}, Sxi)};
			const ekf::Augmentation poses = ekf::objectPoseAugmentations(P, feats, lins, {0, 4}, 6);
			RowMatrixXd out(keep.size(), keep.size());
			ekf::assembleExtended(P, feats, poses, keep, out);
			VectorXd xb(kN + feats.mean.size() + poses.mean.size());
			xb << x, feats.mean, poses.mean;

			ASSERT_EQ(xb.size(), xd.size());
			const double e = std::max(relErr(xb(keep), xd(keep)), relErr(out, Pd(keep, keep)));
			EXPECT_LE(e, 1e-12) << "trial " << trial;
			EXPECT_LE(relErr(out, out.transpose()), 1e-15) << "assembled covariance not symmetric";
			worst = std::max(worst, e);
		}
	core_test::reportWorst("batched vs sequential augmentation", worst);
}

TEST(BatchedAugmentation, ExtendedRowsAndAssembleAreExactCopies)
{
	dynslam_test::rng(914);
	const RowMatrixXd P = core_test::randomSPD(7);
	ekf::Augmentation a, b;
	a.mean = core_test::randomVector(3, -1, 1);
	a.cross = MatrixXd::Random(3, 7);
	a.cov = core_test::randomSPD(3);
	b.mean = core_test::randomVector(2, -1, 1);
	b.cross = MatrixXd::Random(2, 10);
	b.cov = core_test::randomSPD(2);
	RowMatrixXd dense(12, 12);
	dense << P, a.cross.transpose(), b.cross.leftCols(7).transpose(), a.cross, a.cov,
	    b.cross.rightCols(3).transpose(), b.cross, b.cov;
	const std::vector<int> idx{8, 0, 6, 7, 2};
	EXPECT_EQ(ekf::extendedRows(P, a, idx), MatrixXd(dense(idx, Eigen::seqN(0, 10))));
	for (const std::vector<int>& keep :
	     {std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11},
	      std::vector<int>{0, 2, 3, 5, 9, 11}, std::vector<int>{1, 2, 3}, std::vector<int>{7, 8},
	      std::vector<int>{4, 10, 11}})
	{
		RowMatrixXd out(keep.size(), keep.size());
		ekf::assembleExtended(P, a, b, keep, out);
		EXPECT_EQ(out, RowMatrixXd(dense(keep, keep)));
	}
	// b without entries: the state extended by a only
	const std::vector<int> keep{0, 3, 8, 9};
	RowMatrixXd out(4, 4);
	ekf::assembleExtended(P, a, ekf::Augmentation(), keep, out);
	EXPECT_EQ(out, RowMatrixXd(dense(keep, keep)));
}

TEST(BatchedAugmentation, PosesArePlacedBetweenIndependentPads)
{
	dynslam_test::rng(915);
	const RowMatrixXd P = core_test::randomSPD(13, 0.1);
	VectorXd x(13);
	x << core_test::randomPose(), core_test::randomVector(10, -20, 20);
	ekf::Augmentation a;  // nothing pending
	a.mean.resize(0);
	a.cross.resize(0, 13);
	a.cov.resize(0, 0);
	// a rigid object (features 3, 5 at time 0; 7, 9 at time t) and a translation-only one
	const std::vector<ekf::ObjectPoseLinearization> lins = {
	    ekf::linearizeObjectPose(x, {3, 5}, {7, 9}, {}, Eigen::Matrix2d::Identity() * 0.1),
	    ekf::linearizeObjectPose(x, {11}, {1}, {}, Eigen::Matrix2d::Identity() * 0.1)};
	const ekf::Augmentation p = ekf::objectPoseAugmentations(P, a, lins, {0, 4}, 7);
	const std::vector<int> entries{0, 1, 2, 4, 5};
	for (int pad : {3, 6})
	{
		EXPECT_EQ(p.mean[pad], 0.0);
		EXPECT_EQ(p.cross.row(pad).cwiseAbs().maxCoeff(), 0.0);
		EXPECT_EQ(p.cov(pad, pad), 1.0);
		EXPECT_EQ(p.cov.row(pad).cwiseAbs().sum(), 1.0);
		EXPECT_EQ(p.cov.col(pad).cwiseAbs().sum(), 1.0);
	}
	// the poses equal the single-object augmentation
	for (size_t o = 0; o < 2; ++o)
	{
		const ekf::Augmentation one =
		    o == 0 ? ekf::objectPoseAugmentation(x, P, {3, 5}, {7, 9}, {},
		                                         Eigen::Matrix2d::Identity() * 0.1)
		           : ekf::objectPoseAugmentation(x, P, {11}, {1}, {},
		                                         Eigen::Matrix2d::Identity() * 0.1);
		const Eigen::Index r = o == 0 ? 0 : 4, d = one.mean.size();
		EXPECT_LE((p.mean.segment(r, d) - one.mean).cwiseAbs().maxCoeff(), 1e-14);
		EXPECT_LE((p.cross.middleRows(r, d) - one.cross).cwiseAbs().maxCoeff(), 1e-14);
		EXPECT_LE((p.cov.block(r, r, d, d) - one.cov).cwiseAbs().maxCoeff(), 1e-14);
	}
}

TEST(BatchedAugmentation, RejectsInconsistentInput)
{
	const RowMatrixXd P = RowMatrixXd::Identity(4, 4);
	ekf::Augmentation a;
	a.mean = VectorXd::Zero(2);
	a.cross = MatrixXd::Zero(2, 4);
	a.cov = MatrixXd::Identity(2, 2);
	const ekf::Augmentation none;
	RowMatrixXd out(3, 3);
	EXPECT_THROW(ekf::assembleExtended(P, a, none, {0, 2, 1}, out), std::invalid_argument);
	EXPECT_THROW(ekf::assembleExtended(P, a, none, {0, 1, 6}, out), std::out_of_range);
	RowMatrixXd wrong(2, 2);
	EXPECT_THROW(ekf::assembleExtended(P, a, none, {0, 1, 5}, wrong), std::invalid_argument);
	ekf::Augmentation b = a;  // b.cross must have 4 + 2 columns
	EXPECT_THROW(ekf::assembleExtended(P, a, b, {0, 1, 5}, out), std::invalid_argument);
	EXPECT_THROW(ekf::extendedRows(P, a, {6}), std::out_of_range);
	VectorXd x(4);
	x << 0, 0, 0, 1;
	const RowMatrixXd P3 = RowMatrixXd::Identity(4, 4);
	ekf::Augmentation empty;
	empty.cross.resize(0, 4);
	const auto lin = ekf::linearizeObjectPose(x, {2}, {2}, {}, Eigen::Matrix2d::Identity());
	EXPECT_THROW(ekf::objectPoseAugmentations(P3, empty, {lin}, {1}, 2), std::invalid_argument);
	EXPECT_THROW(ekf::objectPoseAugmentations(P3, empty, {lin, lin}, {0, 1}, 4),
	             std::invalid_argument);
	EXPECT_THROW(ekf::objectPoseAugmentations(P3, empty, {lin}, {}, 2), std::invalid_argument);
}
