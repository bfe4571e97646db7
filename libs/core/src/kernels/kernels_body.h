/** The kernels of dynslam/core/kernels.h, included once per ISA variant by kernels_<isa>.cpp, which
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
/** The update's temporaries, kept per thread between calls in one buffer that only grows, so a
 * step allocates nothing once the largest sizes have been seen (Eigen's own matrices reallocate
 * at every change of size, i.e. at nearly every step). The views have the storage orders of the
 * plain types the expressions of before evaluated into (PHt, S, W column-major; P[:, idx] and
 * the solve's result row-major), each starts a multiple of 8 doubles
 * after the buffer's aligned start, and the Cholesky factor is
 * computed in place (LLT<Ref>): the same arithmetic (test
 * KernelIsa.Sse2VariantIsBitIdenticalToTheCodeBefore). */
::Eigen::VectorXd& updateBuffer()
{
	static thread_local ::Eigen::VectorXd buffer;
	return buffer;
}
using ColView = ::Eigen::Map<::Eigen::MatrixXd>;
using RowView = ::Eigen::Map<RowMatrixXd>;
using VecView = ::Eigen::Map<::Eigen::VectorXd>;
}  // namespace

bool sparseUpdate(const TSparseUpdateArgs& a, double& nis)
{
	::Eigen::Map<::Eigen::VectorXd> x(a.x, a.n);
	RowMap P(a.P, a.n, a.n, ::Eigen::OuterStride<>(a.ldP));
	const IndexMap idx(a.idx, a.k);
	const ColMap H(a.H, a.m, a.k), R(a.R, a.m, a.m);
	const ::Eigen::Map<const ::Eigen::VectorXd> nu(a.nu, a.m);

	const ::Eigen::Index n = a.n, m = a.m, k = a.k;
	const auto up8 = [](::Eigen::Index s) { return (s + 7) / 8 * 8; };
	const ::Eigen::Index oPHt = up8(n * k), oS = oPHt + up8(n * m), oS2 = oS + up8(m * m),
	                     oW = oS2 + up8(m * m), oWt = oW + up8(n * m), ov = oWt + up8(m * n),
	                     total = ov + up8(m);
	::Eigen::VectorXd& buf = updateBuffer();
	if (buf.size() < total) buf.resize(total + total / 2);
	double* b = buf.data();
	RowView Pidx(b, n, k);
	ColView PHt(b + oPHt, n, m), S(b + oS, m, m), S2(b + oS2, m, m), W(b + oW, n, m);
	RowView Wt(b + oWt, m, n);
	VecView v(b + ov, m);

	Pidx = P(::Eigen::all, idx);
	PHt.noalias() = Pidx * H.transpose();  // n x m
	S = H * PHt(idx, ::Eigen::all) + R;
	S2 = S + S.transpose();
	S = 0.5 * S2;
	::Eigen::LLT<::Eigen::Ref<::Eigen::MatrixXd>> llt(S);  // in place: S holds L
	if (llt.info() != ::Eigen::Success) return false;
	// W = PHt L^-T: K = W L^-1, K nu = W (L^-1 nu), K S K^T = W W^T. The solve is what
	// solve(PHt^T) evaluates (copy, then in place, in the solve's own plain type).
	Wt = PHt.transpose();
	llt.matrixL().solveInPlace(Wt);
	W = Wt.transpose();  // n x m
	v = nu;
	llt.matrixL().solveInPlace(v);
	x.noalias() += W * v;
	P.selfadjointView<::Eigen::Lower>().rankUpdate(W, -1.0);
	mirrorLowerToUpper(a.P, a.n, a.ldP);
	nis = v.squaredNorm();
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

void productColRow(const double* A, std::ptrdiff_t r, std::ptrdiff_t k, const double* B,
                   std::ptrdiff_t c, std::ptrdiff_t ldB, double* C)
{
	const ColMap Am(A, r, k);
	const ::Eigen::Map<const RowMatrixXd, 0, ::Eigen::OuterStride<>> Bm(
	    B, k, c, ::Eigen::OuterStride<>(ldB));
	::Eigen::Map<::Eigen::MatrixXd> Cm(C, r, c);
	Cm.noalias() = Am * Bm;
}
}  // namespace dynslam::kernels::DYNSLAM_KERNEL_NS
