/** The in-place commit (doc/results/performance.md, section 10): ekf::assembleInPlace equals
 * ekf::assembleExtended bit for bit, in a buffer with an outer stride larger than the matrix,
 * and ekf::CSquareBuffer keeps its contents while a size fits its side and reuses the buffers
 * freed in the same thread. */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/square_buffer.h>
#include <gtest/gtest.h>

#include <thread>

#include "core_test_utils.h"

using namespace dynslam;
using dynslam::ekf::RowMatrixXd;
using Eigen::MatrixXd;

TEST(SquareBuffer, AssembleInPlaceEqualsAssembleExtended)
{
	dynslam_test::rng(1021);
	const Eigen::Index n = 9, stride = 16;
	const RowMatrixXd P = core_test::randomSPD(n);
	ekf::Augmentation a, b;
	a.mean = core_test::randomVector(3, -1, 1);
	a.cross = MatrixXd::Random(3, n);
	a.cov = core_test::randomSPD(3);
	b.mean = core_test::randomVector(2, -1, 1);
	b.cross = MatrixXd::Random(2, n + 3);
	b.cov = core_test::randomSPD(2);
	const std::vector<std::vector<int>> keeps{
	    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13},  // nothing dropped: old block stays
	    {0, 1, 2, 3, 4, 5, 6, 7, 8},                     // nothing added
	    {0, 1, 2, 5, 6, 7, 8, 9, 10, 12},                // old entries 3, 4 and new ones dropped
	    {0, 2, 4, 6, 8, 11, 13},                         // every other entry
	    {1, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13},        // the first dropped: everything moves
	    {9, 10, 13}};                                    // only new entries
	for (const auto& keep : keeps)
	{
		const Eigen::Index k = Eigen::Index(keep.size());
		RowMatrixXd expected(k, k);
		ekf::assembleExtended(P, a, b, keep, expected);
		std::vector<double> buf(size_t(stride * stride), -7.0);
		Eigen::Map<RowMatrixXd, 0, Eigen::OuterStride<>>(buf.data(), n, n,
		                                                 Eigen::OuterStride<>(stride)) = P;
		ekf::assembleInPlace(buf.data(), stride, n, a, b, keep);
		const RowMatrixXd got = Eigen::Map<RowMatrixXd, 0, Eigen::OuterStride<>>(
		    buf.data(), k, k, Eigen::OuterStride<>(stride));
		EXPECT_EQ(got, expected) << "keep of " << k;
		// only the k x k block of the buffer is written
		for (Eigen::Index i = 0; i < stride; ++i)
			for (Eigen::Index j = std::max(n, k); j < stride; ++j)
				EXPECT_EQ(buf[size_t(i * stride + j)], -7.0);
	}
	std::vector<double> buf(size_t(stride * stride));
	EXPECT_THROW(ekf::assembleInPlace(buf.data(), n - 1, n, a, b, keeps[1]), std::invalid_argument);
	EXPECT_THROW(ekf::assembleInPlace(buf.data(), stride, n, a, b, {0, 2, 1}),
	             std::invalid_argument);
	EXPECT_THROW(ekf::assembleInPlace(buf.data(), stride, n, a, b, {0, 1, 14}), std::out_of_range);
}

TEST(SquareBuffer, KeepsItsContentsWhileTheSizeFitsItsSide)
{
	ekf::CSquareBuffer B;
	B.resize(10);
	EXPECT_GE(B.stride(), 64);
	EXPECT_EQ(B.stride() % 8, 0);  // every row at the same alignment
	for (Eigen::Index i = 0; i < 10; ++i)
		for (Eigen::Index j = 0; j < 10; ++j) B.view()(i, j) = double(100 * i + j);
	const double* data = B.data();
	B.resize(40);  // grows in place
	EXPECT_EQ(B.data(), data);
	EXPECT_EQ(B.view()(9, 7), 907.0);
	B.resize(5);
	EXPECT_EQ(B.view()(4, 3), 403.0);
	B.resize(100);  // outgrows the side: a new buffer, side n + n / 2 rounded up to 8
	EXPECT_NE(B.data(), data);
	EXPECT_EQ(B.stride(), 152);
	EXPECT_TRUE(B.keeps(152));
	EXPECT_FALSE(B.keeps(153));
	EXPECT_FALSE(B.keeps(30));  // 30^2 < 152^2 / 16: the memory of a larger state is given back
}

TEST(SquareBuffer, ReusesTheBuffersFreedInTheSameThread)
{
	const double* first = nullptr;
	{
		ekf::CSquareBuffer B;
		B.resize(200);
		first = B.data();
	}
	ekf::CSquareBuffer C;
	C.resize(190);  // fits the freed buffer: reused
	EXPECT_EQ(C.data(), first);
	EXPECT_EQ(C.stride(), 304);
	// another thread has its own cache
	const double* other = nullptr;
	std::thread t(
	    [&]
	    {
		    ekf::CSquareBuffer D;
		    D.resize(190);
		    other = D.data();
	    });
	t.join();
	EXPECT_NE(other, first);
	C.release();
	EXPECT_EQ(C.rows(), 0);
}
