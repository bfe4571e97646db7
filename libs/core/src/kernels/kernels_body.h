/** The kernels of dynslam/kernels.h, included once per ISA variant by kernels_<isa>.cpp, which
 * defines DYNSLAM_KERNEL_NS (the variant's namespace) first. No include guard on purpose.
 * Everything here is Eigen and raw storage only: in the AVX2 variant "Eigen" is a renamed
 * namespace (kernels_avx2.cpp), so no type or template of the rest of the program may appear. */
#ifndef DYNSLAM_KERNEL_NS
#error "kernels_body.h: define DYNSLAM_KERNEL_NS first (kernels_sse2.cpp, kernels_avx2.cpp)"
#endif

#include <Eigen/Cholesky>
#include <Eigen/Core>
#if defined(__SSE2__) || defined(__AVX__)
#include <immintrin.h>
#endif

#include "variants.h"

namespace dynslam::kernels::DYNSLAM_KERNEL_NS
{
namespace
{
using RowMatrixXd = ::Eigen::Matrix<double, ::Eigen::Dynamic, ::Eigen::Dynamic, ::Eigen::RowMajor>;
using RowMap = ::Eigen::Map<RowMatrixXd, 0, ::Eigen::OuterStride<>>;
using ColMap = ::Eigen::Map<const ::Eigen::MatrixXd>;
using IndexMap = ::Eigen::Map<const ::Eigen::VectorXi>;

/** The 4 x 4 block at src (row stride ld) written transposed at dst (row stride ld): copies
 * only. AVX: four loads, eight shuffles, four stores; SSE2: the same as four 2 x 2 blocks. */
inline void transposeBlock4(const double* src, double* dst, ::Eigen::Index ld)
{
#if defined(__AVX__)
	const __m256d r0 = _mm256_loadu_pd(src), r1 = _mm256_loadu_pd(src + ld),
	              r2 = _mm256_loadu_pd(src + 2 * ld), r3 = _mm256_loadu_pd(src + 3 * ld);
	const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1),
	              t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
	_mm256_storeu_pd(dst, _mm256_permute2f128_pd(t0, t2, 0x20));
	_mm256_storeu_pd(dst + ld, _mm256_permute2f128_pd(t1, t3, 0x20));
	_mm256_storeu_pd(dst + 2 * ld, _mm256_permute2f128_pd(t0, t2, 0x31));
	_mm256_storeu_pd(dst + 3 * ld, _mm256_permute2f128_pd(t1, t3, 0x31));
#elif defined(__SSE2__)
	for (int bi = 0; bi < 4; bi += 2)
		for (int bj = 0; bj < 4; bj += 2)
		{
			const double* s = src + bi * ld + bj;
			const __m128d r0 = _mm_loadu_pd(s), r1 = _mm_loadu_pd(s + ld);
			double* d = dst + bj * ld + bi;
			_mm_storeu_pd(d, _mm_unpacklo_pd(r0, r1));
			_mm_storeu_pd(d + ld, _mm_unpackhi_pd(r0, r1));
		}
#else
	for (int i = 0; i < 4; ++i)
		for (int j = 0; j < 4; ++j) dst[j * ld + i] = src[i * ld + j];
#endif
}

/** P(j, i) = P(i, j) for j < i (row-major, row stride ld): the lower triangle copied onto the
 * upper one, in 16 x 16 tiles (the strided side of a tile stays in the L1 cache) of 4 x 4
 * blocks transposed in registers (transposeBlock4); the 4 x 4 blocks on the diagonal and the
 * last n % 4 rows element by element. Copies only: the result is the same as the plain loop's,
 * bit for bit. No std:: templates here (weak symbols, see kernels_avx2.cpp). */
void mirrorLowerToUpper(double* P, ::Eigen::Index n, ::Eigen::Index ld)
{
	constexpr ::Eigen::Index T = 16;
	const ::Eigen::Index n4 = n - n % 4;
	for (::Eigen::Index i0 = 0; i0 < n4; i0 += T)
	{
		const ::Eigen::Index i1 = i0 + T < n4 ? i0 + T : n4;
		for (::Eigen::Index j0 = 0; j0 <= i0; j0 += T)
			for (::Eigen::Index i = i0; i < i1; i += 4)
			{
				const ::Eigen::Index j1 = j0 + T < i ? j0 + T : i;  // blocks strictly below
				for (::Eigen::Index j = j0; j < j1; j += 4)
					transposeBlock4(P + i * ld + j, P + j * ld + i, ld);
			}
	}
	for (::Eigen::Index i = 0; i < n4; i += 4)  // inside the diagonal blocks
		for (::Eigen::Index r = 1; r < 4; ++r)
			for (::Eigen::Index c = 0; c < r; ++c)
				P[(i + c) * ld + i + r] = P[(i + r) * ld + i + c];
	for (::Eigen::Index i = n4; i < n; ++i)  // the last rows: every column before the diagonal
	{
		const double* src = P + i * ld;
		for (::Eigen::Index j = 0; j < i; ++j) P[j * ld + i] = src[j];
	}
}
/** The update's temporaries, kept per thread between calls (no allocation while the sizes do
 * not grow). The types are those the expressions of before evaluated into, so the arithmetic
 * is unchanged: PHt, S and W column-major, the solve's result in the plain type of
 * solve(PHt^T) (row-major m x n). */
struct TUpdateWorkspace
{
	RowMatrixXd Pidx;  // P[:, idx], the plain type the product evaluated the gather into
	::Eigen::MatrixXd PHt, S, S2, W;
	decltype(::Eigen::LLT<::Eigen::MatrixXd>().matrixL().solve(
	    ::Eigen::MatrixXd().transpose()))::PlainObject Wt;
	::Eigen::VectorXd v;
	::Eigen::LLT<::Eigen::MatrixXd> llt;
};

TUpdateWorkspace& updateWorkspace()
{
	static thread_local TUpdateWorkspace w;
	return w;
}
}  // namespace

bool sparseUpdate(const TSparseUpdateArgs& a, double& nis)
{
	::Eigen::Map<::Eigen::VectorXd> x(a.x, a.n);
	RowMap P(a.P, a.n, a.n, ::Eigen::OuterStride<>(a.ldP));
	const IndexMap idx(a.idx, a.k);
	const ColMap H(a.H, a.m, a.k), R(a.R, a.m, a.m);
	const ::Eigen::Map<const ::Eigen::VectorXd> nu(a.nu, a.m);

	TUpdateWorkspace& w = updateWorkspace();
	w.Pidx = P(::Eigen::all, idx);
	w.PHt.noalias() = w.Pidx * H.transpose();  // n x m
	w.S = H * w.PHt(idx, ::Eigen::all) + R;
	w.S2 = w.S + w.S.transpose();
	w.S = 0.5 * w.S2;
	w.llt.compute(w.S);
	if (w.llt.info() != ::Eigen::Success) return false;
	// W = PHt L^-T: K = W L^-1, K nu = W (L^-1 nu), K S K^T = W W^T. The solve is what
	// solve(PHt^T) evaluates (copy, then in place, in the solve's own plain type).
	w.Wt = w.PHt.transpose();
	w.llt.matrixL().solveInPlace(w.Wt);
	w.W = w.Wt.transpose();  // n x m
	w.v = nu;
	w.llt.matrixL().solveInPlace(w.v);
	x.noalias() += w.W * w.v;
	P.selfadjointView<::Eigen::Lower>().rankUpdate(w.W, -1.0);
	mirrorLowerToUpper(a.P, a.n, a.ldP);
	nis = w.v.squaredNorm();
	return true;
}

void expandLevel(const TExpandLevelArgs& a)
{
	const ColMap G(a.G, a.nf, a.m0), Q(a.Q, a.m0, a.m0), cross(a.cross, a.m0, a.p),
	    P(a.P, a.p, a.p);
	const ::Eigen::Map<const ::Eigen::VectorXd> beta(a.beta, a.m0), x(a.x, a.p);
	::Eigen::Map<::Eigen::VectorXd> xB(a.xB, a.p);
	::Eigen::Map<::Eigen::MatrixXd> CB(a.CB, a.nf, a.p), BB(a.BB, a.p, a.p);
	xB = x + cross.transpose() * beta;
	CB = G * cross;
	BB = P + cross.transpose() * (Q * cross);
	BB = 0.5 * (BB + BB.transpose()).eval();
}
}  // namespace dynslam::kernels::DYNSLAM_KERNEL_NS
