/** The dispatched kernels (dynslam/core/kernels.h): the ISA choice, and the AVX2/FMA variant equal
 * to the SSE2 one within 1e-12 (relative) on random inputs. The comparisons need a CPU with AVX2
 * and FMA and a build with the AVX2 variant: elsewhere they are skipped (GTEST_SKIP, with the
 * reason). */
#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/kernels.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <iostream>
#include <numeric>
#include <random>
#include <stdexcept>
#include <tuple>

using namespace dynslam;
using kernels::Isa;

namespace
{
#define SKIP_WITHOUT_AVX2()                                      \
	if (!kernels::isaAvailable(Isa::Avx2))                       \
	GTEST_SKIP() << "AVX2/FMA variant not available (compiled: " \
	             << kernels::isaCompiled(Isa::Avx2)              \
	             << ", CPU has AVX2 and FMA: " << kernels::cpuSupports(Isa::Avx2) << ")"

struct TCase
{
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;  ///< with extra columns: the kernels see an outer stride > n
	std::vector<int> idx;
	Eigen::MatrixXd H, R;
	Eigen::VectorXd nu;
};

/** A random EKF update of the sparseUpdate form: n-entry state, k observed entries (ego + pairs
 * at random places), m = k - 1 rows. P is stored with `pad` unused columns after each row. */
TCase randomCase(int n, int pairs, int pad, unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> u(-1, 1);
	TCase c;
	c.x = Eigen::VectorXd::NullaryExpr(n, [&] { return 10 * u(rng); });
	Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
	Eigen::MatrixXd S = A * A.transpose() / n + 0.1 * Eigen::MatrixXd::Identity(n, n);
	S = 0.5 * (S + S.transpose()).eval();
	c.P = ekf::RowMatrixXd::Constant(n, n + pad, 7.0);  // the padding must stay untouched
	c.P.leftCols(n) = S;
	std::vector<int> landmarks((n - 3) / 2);
	std::iota(landmarks.begin(), landmarks.end(), 0);
	std::shuffle(landmarks.begin(), landmarks.end(), rng);
	landmarks.resize(size_t(pairs));
	std::sort(landmarks.begin(), landmarks.end());
	c.idx = {0, 1, 2};
	for (const int l : landmarks) c.idx.insert(c.idx.end(), {3 + 2 * l, 4 + 2 * l});
	const int k = int(c.idx.size()), m = 2 * pairs;
	c.H = Eigen::MatrixXd::NullaryExpr(m, k, [&] { return u(rng); });
	c.nu = Eigen::VectorXd::NullaryExpr(m, [&] { return 0.5 * u(rng); });
	Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(m, m, [&] { return u(rng); });
	c.R = 0.01 * (B * B.transpose() + Eigen::MatrixXd::Identity(m, m));
	return c;
}

/** Runs ekf::sparseUpdate with `isa` on a copy of c; returns (x, P incl. padding) and NIS. */
struct TResult
{
	Eigen::VectorXd x;
	ekf::RowMatrixXd P;
	double nis = 0;
};
TResult run(const TCase& c, Isa isa)
{
	kernels::CScopedIsa scoped(isa);
	TResult r{c.x, c.P, 0};
	const Eigen::Index n = c.x.size();
	Eigen::Map<ekf::RowMatrixXd, 0, Eigen::OuterStride<>> view(r.P.data(), n, n,
	                                                           Eigen::OuterStride<>(r.P.cols()));
	r.nis = ekf::sparseUpdate(r.x, view, c.idx, c.H, c.nu, c.R);
	return r;
}

/** The arithmetic of ekf::sparseUpdate as it was written before the kernels were dispatched
 * (Eigen in this test's translation unit, baseline flags). */
double sparseUpdateBefore(Eigen::VectorXd& x, Eigen::Ref<ekf::RowMatrixXd> P,
                          const std::vector<int>& idx, const Eigen::MatrixXd& H,
                          const Eigen::VectorXd& nu, const Eigen::MatrixXd& R)
{
	const Eigen::MatrixXd PHt = P(Eigen::all, idx) * H.transpose();
	Eigen::MatrixXd S = H * PHt(idx, Eigen::all) + R;
	S = 0.5 * (S + S.transpose()).eval();
	const Eigen::LLT<Eigen::MatrixXd> llt(S);
	const Eigen::MatrixXd W = llt.matrixL().solve(PHt.transpose()).transpose();
	const Eigen::VectorXd v = llt.matrixL().solve(nu);
	x.noalias() += W * v;
	P.selfadjointView<Eigen::Lower>().rankUpdate(W, -1.0);
	for (Eigen::Index i = 0; i + 1 < P.rows(); ++i)
		P.row(i).tail(P.rows() - 1 - i) = P.col(i).tail(P.rows() - 1 - i).transpose();
	return v.squaredNorm();
}

/** A random level of the global update (kernels::expandLevel) and its result per variant. */
struct TLevel
{
	Eigen::MatrixXd G, Q, cross, P;
	Eigen::VectorXd beta, x;
};
TLevel randomLevel(int nf, int m0, int p, unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> u(-1, 1);
	const auto M = [&](int r, int c)
	{ return Eigen::MatrixXd::NullaryExpr(r, c, [&] { return u(rng); }); };
	TLevel l{M(nf, m0), M(m0, m0), M(m0, p), M(p, p), M(m0, 1), M(p, 1)};
	l.Q = l.Q * l.Q.transpose();
	l.P = l.P * l.P.transpose();
	return l;
}
struct TLevelOut
{
	Eigen::VectorXd xB;
	Eigen::MatrixXd CB, BB;
};
TLevelOut expand(const TLevel& l, Isa isa)
{
	kernels::CScopedIsa scoped(isa);
	TLevelOut o{Eigen::VectorXd(l.x.size()), Eigen::MatrixXd(l.G.rows(), l.P.rows()),
	            Eigen::MatrixXd(l.P.rows(), l.P.rows())};
	kernels::TExpandLevelArgs k;
	k.G = l.G.data();
	k.nf = l.G.rows();
	k.m0 = l.Q.rows();
	k.Q = l.Q.data();
	k.beta = l.beta.data();
	k.cross = l.cross.data();
	k.p = l.P.rows();
	k.P = l.P.data();
	k.x = l.x.data();
	k.xB = o.xB.data();
	k.CB = o.CB.data();
	k.BB = o.BB.data();
	kernels::expandLevel(k);
	return o;
}

double relDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
	return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}
}  // namespace

TEST(KernelIsa, NamesParseAndBadValuesAreClearErrors)
{
	EXPECT_EQ(kernels::parseIsa("sse2"), Isa::Sse2);
	EXPECT_EQ(kernels::parseIsa("avx2"), Isa::Avx2);
	EXPECT_STREQ(kernels::isaName(Isa::Avx2), "avx2");
	EXPECT_STREQ(kernels::isaName(Isa::Sse2), "sse2");
	try
	{
		kernels::isaFromEnvironmentValue("avx512");
		FAIL() << "no error for DYNSLAM_ISA = avx512";
	}
	catch (const std::runtime_error& e)
	{
		EXPECT_NE(std::string(e.what()).find("DYNSLAM_ISA = 'avx512'"), std::string::npos)
		    << e.what();
	}
	EXPECT_THROW(kernels::parseIsa("AVX2"), std::runtime_error);
	// The portable variant is always there; unset / empty / auto = the best available one.
	EXPECT_TRUE(kernels::isaAvailable(Isa::Sse2));
	EXPECT_EQ(kernels::isaFromEnvironmentValue(nullptr), kernels::bestIsa());
	EXPECT_EQ(kernels::isaFromEnvironmentValue(""), kernels::bestIsa());
	EXPECT_EQ(kernels::isaFromEnvironmentValue("auto"), kernels::bestIsa());
	EXPECT_EQ(kernels::isaFromEnvironmentValue("sse2"), Isa::Sse2);
	if (kernels::isaAvailable(Isa::Avx2))
	{
		EXPECT_EQ(kernels::bestIsa(), Isa::Avx2);
		EXPECT_EQ(kernels::isaFromEnvironmentValue("avx2"), Isa::Avx2);
	}
	else
	{
		EXPECT_THROW(kernels::isaFromEnvironmentValue("avx2"), std::runtime_error);
		EXPECT_THROW(kernels::setActiveIsa(Isa::Avx2), std::runtime_error);
	}
}

TEST(KernelIsa, ScopedChoiceIsRestored)
{
	const Isa before = kernels::activeIsa();
	{
		kernels::CScopedIsa s(Isa::Sse2);
		EXPECT_EQ(kernels::activeIsa(), Isa::Sse2);
	}
	EXPECT_EQ(kernels::activeIsa(), before);
}

// The AVX2 variant equals the SSE2 one within 1e-12 relative (measured: a few 1e-16), from tiny
// to cache-sized states, with a padded row stride; and it is really another code path: FMA
// rounds differently, so the results are not all bit-identical (a dispatcher that always ran
// the SSE2 variant would fail here).
TEST(KernelIsa, Avx2SparseUpdateEqualsSse2OnRandomInputs)
{
	SKIP_WITHOUT_AVX2();
	double worstX = 0, worstP = 0, worstNis = 0;
	bool anyBitDiffers = false;
	unsigned seed = 11;
	for (const auto& [n, pairs, pad] : std::vector<std::tuple<int, int, int>>{
	         {5, 1, 0}, {23, 4, 3}, {63, 10, 0}, {203, 7, 5}, {403, 20, 1}})
	{
		const TCase c = randomCase(n, pairs, pad, seed++);
		const TResult s = run(c, Isa::Sse2), a = run(c, Isa::Avx2);
		worstX = std::max(worstX, relDiff(a.x, s.x));
		worstP = std::max(worstP, relDiff(a.P, s.P));
		worstNis = std::max(worstNis, std::abs(a.nis - s.nis) / s.nis);
		EXPECT_TRUE((s.P.rightCols(pad).array() == 7.0).all()) << "padding written, n = " << n;
		EXPECT_TRUE((a.P.rightCols(pad).array() == 7.0).all()) << "padding written, n = " << n;
		EXPECT_TRUE(a.P.leftCols(n).isApprox(a.P.leftCols(n).transpose(), 0))
		    << "not exactly symmetric, n = " << n;
		anyBitDiffers = anyBitDiffers || (a.P.array() != s.P.array()).any();
	}
	EXPECT_LE(worstX, 1e-12);
	EXPECT_LE(worstP, 1e-12);
	EXPECT_LE(worstNis, 1e-12);
	EXPECT_TRUE(anyBitDiffers) << "the AVX2 path gave bit-identical results: not dispatched?";
	std::cout << "[ measured ] AVX2 vs SSE2: x " << worstX << ", P " << worstP << ", NIS "
	          << worstNis << " (relative)\n";
}

// Both variants refuse a non-positive-definite innovation covariance alike, leaving x and P.
TEST(KernelIsa, BothVariantsRejectAnIndefiniteInnovation)
{
	for (const Isa isa : {Isa::Sse2, Isa::Avx2})
	{
		if (!kernels::isaAvailable(isa)) continue;
		TCase c = randomCase(23, 2, 0, 5);
		c.R = -100 * Eigen::MatrixXd::Identity(c.R.rows(), c.R.cols());
		kernels::CScopedIsa scoped(isa);
		Eigen::VectorXd x = c.x;
		ekf::RowMatrixXd P = c.P;
		EXPECT_THROW(ekf::sparseUpdate(x, P, c.idx, c.H, c.nu, c.R), std::runtime_error)
		    << kernels::isaName(isa);
		EXPECT_EQ(x, c.x);
		EXPECT_EQ(P, c.P);
	}
}

// The SSE2 variant is the arithmetic of before, bit for bit (the default path's results did not
// change when the kernels were moved into their own translation units).
TEST(KernelIsa, Sse2VariantIsBitIdenticalToTheCodeBefore)
{
	unsigned seed = 21;
	for (const auto& [n, pairs, pad] :
	     std::vector<std::tuple<int, int, int>>{{23, 4, 3}, {203, 7, 0}, {403, 20, 1}})
	{
		const TCase c = randomCase(n, pairs, pad, seed++);
		const TResult s = run(c, Isa::Sse2);
		TResult b{c.x, c.P, 0};
		Eigen::Map<ekf::RowMatrixXd, 0, Eigen::OuterStride<>> view(
		    b.P.data(), n, n, Eigen::OuterStride<>(b.P.cols()));
		b.nis = sparseUpdateBefore(b.x, view, c.idx, c.H, c.nu, c.R);
		EXPECT_TRUE((s.x.array() == b.x.array()).all()) << "n = " << n;
		EXPECT_TRUE((s.P.array() == b.P.array()).all()) << "n = " << n;
		EXPECT_EQ(s.nis, b.nis);
	}
	const TLevel l = randomLevel(131, 130, 300, 4);
	const TLevelOut s = expand(l, Isa::Sse2);
	const Eigen::VectorXd xB = l.x + l.cross.transpose() * l.beta;
	const Eigen::MatrixXd CB = l.G * l.cross;
	Eigen::MatrixXd BB = l.P + l.cross.transpose() * (l.Q * l.cross);
	BB = 0.5 * (BB + BB.transpose()).eval();
	EXPECT_TRUE((s.xB.array() == xB.array()).all());
	EXPECT_TRUE((s.CB.array() == CB.array()).all());
	EXPECT_TRUE((s.BB.array() == BB.array()).all());
}

TEST(KernelIsa, Avx2ExpandLevelEqualsSse2OnRandomInputs)
{
	SKIP_WITHOUT_AVX2();
	double worst = 0;
	bool anyBitDiffers = false;
	unsigned seed = 31;
	for (const auto& [nf, m0, p] :
	     std::vector<std::tuple<int, int, int>>{{3, 2, 4}, {40, 30, 50}, {131, 130, 600}})
	{
		const TLevel l = randomLevel(nf, m0, p, seed++);
		const TLevelOut s = expand(l, Isa::Sse2), a = expand(l, Isa::Avx2);
		worst = std::max({worst, relDiff(a.xB, s.xB), relDiff(a.CB, s.CB), relDiff(a.BB, s.BB)});
		EXPECT_TRUE(a.BB.isApprox(a.BB.transpose(), 0)) << "not exactly symmetric, p = " << p;
		anyBitDiffers = anyBitDiffers || (a.BB.array() != s.BB.array()).any();
	}
	EXPECT_LE(worst, 1e-12);
	EXPECT_TRUE(anyBitDiffers) << "the AVX2 path gave bit-identical results: not dispatched?";
	std::cout << "[ measured ] expandLevel AVX2 vs SSE2: " << worst << " (relative)\n";
}
