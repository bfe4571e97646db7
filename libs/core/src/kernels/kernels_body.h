/** The kernels of dynslam/kernels.h, included once per ISA variant by kernels_<isa>.cpp, which
 * defines DYNSLAM_KERNEL_NS (the variant's namespace) first. No include guard on purpose.
 * Everything here is Eigen and raw storage only: in the AVX2 variant "Eigen" is a renamed
 * namespace (kernels_avx2.cpp), so no type or template of the rest of the program may appear. */
#ifndef DYNSLAM_KERNEL_NS
#error "kernels_body.h: define DYNSLAM_KERNEL_NS first (kernels_sse2.cpp, kernels_avx2.cpp)"
#endif

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "variants.h"

namespace dynslam::kernels::DYNSLAM_KERNEL_NS
{
namespace
{
using RowMatrixXd = ::Eigen::Matrix<double, ::Eigen::Dynamic, ::Eigen::Dynamic, ::Eigen::RowMajor>;
using RowMap = ::Eigen::Map<RowMatrixXd, 0, ::Eigen::OuterStride<>>;
using ColMap = ::Eigen::Map<const ::Eigen::MatrixXd>;
using IndexMap = ::Eigen::Map<const ::Eigen::VectorXi>;

/** P(j, i) = P(i, j) for j < i (row-major, row stride ld): the lower triangle copied onto the
 * upper one in 16 x 16 tiles, so that the strided side of a tile stays in the L1 cache (a
 * column-at-a-time copy touches every row below the diagonal once per column). Copies only: the
 * result is the same as the plain loop's, bit for bit. No std:: templates here (weak symbols,
 * see kernels_avx2.cpp). */
void mirrorLowerToUpper(double* P, ::Eigen::Index n, ::Eigen::Index ld)
{
	constexpr ::Eigen::Index T = 16;
	for (::Eigen::Index i0 = 0; i0 < n; i0 += T)
	{
		const ::Eigen::Index i1 = i0 + T < n ? i0 + T : n;
		for (::Eigen::Index j0 = 0; j0 <= i0; j0 += T)
			for (::Eigen::Index i = i0; i < i1; ++i)
			{
				const double* src = P + i * ld;
				const ::Eigen::Index j1 = j0 + T < i ? j0 + T : i;
				for (::Eigen::Index j = j0; j < j1; ++j) P[j * ld + i] = src[j];
			}
	}
}
/** The update's temporaries, kept per thread between calls (no allocation while the sizes do
 * not grow). The types are those the expressions of before evaluated into, so the arithmetic
 * is unchanged: PHt, S and W column-major, the solve's result in the plain type of
 * solve(PHt^T) (row-major m x n). */
struct TUpdateWorkspace
{
	::Eigen::MatrixXd PHt, S, W;
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
	w.PHt.noalias() = P(::Eigen::all, idx) * H.transpose();  // n x m
	w.S = H * w.PHt(idx, ::Eigen::all) + R;
	w.S = 0.5 * (w.S + w.S.transpose()).eval();
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
