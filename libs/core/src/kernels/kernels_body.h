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
}  // namespace

bool sparseUpdate(const TSparseUpdateArgs& a, double& nis)
{
	::Eigen::Map<::Eigen::VectorXd> x(a.x, a.n);
	RowMap P(a.P, a.n, a.n, ::Eigen::OuterStride<>(a.ldP));
	const IndexMap idx(a.idx, a.k);
	const ColMap H(a.H, a.m, a.k), R(a.R, a.m, a.m);
	const ::Eigen::Map<const ::Eigen::VectorXd> nu(a.nu, a.m);

	const ::Eigen::MatrixXd PHt = P(::Eigen::all, idx) * H.transpose();  // n x m
	::Eigen::MatrixXd S = H * PHt(idx, ::Eigen::all) + R;
	S = 0.5 * (S + S.transpose()).eval();
	const ::Eigen::LLT<::Eigen::MatrixXd> llt(S);
	if (llt.info() != ::Eigen::Success) return false;
	// W = PHt L^-T: K = W L^-1, K nu = W (L^-1 nu), K S K^T = W W^T.
	const ::Eigen::MatrixXd W = llt.matrixL().solve(PHt.transpose()).transpose();  // n x m
	const ::Eigen::VectorXd v = llt.matrixL().solve(nu);
	x.noalias() += W * v;
	P.selfadjointView<::Eigen::Lower>().rankUpdate(W, -1.0);
	for (::Eigen::Index i = 0; i + 1 < P.rows(); ++i)
		P.row(i).tail(P.rows() - 1 - i) = P.col(i).tail(P.rows() - 1 - i).transpose();
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
}  // namespace dynslam::kernels::DYNSLAM_KERNEL_NS
