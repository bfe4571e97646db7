#include <dynslam/core/ekf_steps.h>
#include <dynslam/core/kernels.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/core/models/smoothing.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace dynslam::ekf
{
using models::Matrix23d;

namespace
{
/** Throws std::out_of_range unless every i in idx satisfies 0 <= i and i + width <= n. */
void checkIndices(const char* fn, const std::vector<int>& idx, Eigen::Index n, int width = 1)
{
	for (int i : idx)
		if (i < 0 || Eigen::Index(i) + width > n)
			throw std::out_of_range(std::string(fn) + ": state index " + std::to_string(i) +
			                        " out of range for " + std::to_string(width) +
			                        " entries in a state of size " + std::to_string(n));
}
}  // namespace

Augmentation featureAugmentation(models::MeasurementModel model, const Eigen::Vector3d& ego,
                                 const Eigen::Ref<const RowMatrixXd>& P_ego_rows,
                                 const std::vector<Eigen::Vector2d>& z, const Eigen::Matrix2d& R,
                                 const Eigen::Vector3d& sensor)
{
	if (P_ego_rows.rows() != 3) throw std::invalid_argument("featureAugmentation: need 3 ego rows");
	const Eigen::Index n = P_ego_rows.cols(), k = Eigen::Index(z.size());
	const Eigen::Matrix3d Pxx = P_ego_rows.leftCols<3>();
	Augmentation a;
	a.mean.resize(2 * k);
	a.cross.resize(2 * k, n);
	a.cov.resize(2 * k, 2 * k);
	std::vector<Matrix23d> Lx(k);
	for (Eigen::Index i = 0; i < k; ++i)
	{
		Eigen::Matrix2d Lz;
		a.mean.segment<2>(2 * i) =
		    models::inverseObserveFromSensor(model, ego, sensor, z[i], &Lx[i], &Lz);
		a.cross.middleRows<2>(2 * i).noalias() = Lx[i] * P_ego_rows;
		a.cov.block<2, 2>(2 * i, 2 * i) = Lx[i] * Pxx * Lx[i].transpose() + Lz * R * Lz.transpose();
		for (Eigen::Index j = 0; j < i; ++j)
		{
			a.cov.block<2, 2>(2 * i, 2 * j) = Lx[i] * Pxx * Lx[j].transpose();
			a.cov.block<2, 2>(2 * j, 2 * i) = a.cov.block<2, 2>(2 * i, 2 * j).transpose();
		}
	}
	return a;
}

ObjectPoseLinearization linearizeObjectPose(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            const std::vector<int>& f0_idx,
                                            const std::vector<int>& ft_idx,
                                            const std::vector<int>& seen,
                                            const Eigen::Matrix2d& Sigma_xi, int centroidCols)
{
	const int n = int(f0_idx.size()), m = int(ft_idx.size());
	if (n < 1 || m < 1) throw std::invalid_argument("objectPoseAugmentation: no features");
	checkIndices("objectPoseAugmentation", f0_idx, x.size(), 2);
	checkIndices("objectPoseAugmentation", ft_idx, x.size(), 2);
	if (n == 1 && (m != 1 || (!seen.empty() && (seen.size() != 1 || seen[0] != 0))))
		throw std::invalid_argument(
		    "objectPoseAugmentation: a one-feature object needs exactly that feature at time t");
	Eigen::Matrix2Xd f0(2, n), ft(2, m);
	for (int k = 0; k < n; ++k) f0.col(k) = x.segment<2>(f0_idx[k]);
	for (int i = 0; i < m; ++i) ft.col(i) = x.segment<2>(ft_idx[i]);

	ObjectPoseLinearization lin;
	Eigen::MatrixXd G1, G2;
	if (n == 1)
	{
		Eigen::Matrix2d g1, g2;
		lin.xi = models::objectTranslationInverse(f0.col(0), ft.col(0), &g1, &g2);
		G1 = g1;
		G2 = g2;
	}
	else
		lin.xi = models::objectPoseInverse(f0, ft, seen, &G1, &G2, centroidCols);

	lin.idx.reserve(2 * (n + m));
	for (int k : f0_idx) lin.idx.insert(lin.idx.end(), {k, k + 1});
	for (int k : ft_idx) lin.idx.insert(lin.idx.end(), {k, k + 1});
	lin.Gamma.resize(lin.xi.size(), 2 * (n + m));
	lin.Gamma << G1, G2;
	lin.noise = Eigen::MatrixXd::Zero(lin.xi.size(), lin.xi.size());
	for (int i = 0; i < m; ++i)
		lin.noise.noalias() +=
		    G2.middleCols<2>(2 * i) * Sigma_xi * G2.middleCols<2>(2 * i).transpose();
	return lin;
}

Augmentation objectPoseAugmentation(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const Eigen::Ref<const RowMatrixXd>& P,
                                    const std::vector<int>& f0_idx, const std::vector<int>& ft_idx,
                                    const std::vector<int>& seen, const Eigen::Matrix2d& Sigma_xi)
{
	if (P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("objectPoseAugmentation: P does not match x");
	// The batched form for one object, on the state extended by nothing.
	const ObjectPoseLinearization lin = linearizeObjectPose(x, f0_idx, ft_idx, seen, Sigma_xi);
	Augmentation none;
	none.cross.resize(0, x.size());
	return objectPoseAugmentations(P, none, {lin}, {0}, lin.xi.size());
}

ObjectPoseLinearization appendJoinedFeatures(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const ObjectPoseLinearization& pose, int nc,
                                             const std::vector<int>& ft_idx, int padTo)
{
	const Eigen::Index d = pose.xi.size(), K = Eigen::Index(pose.idx.size());
	const Eigen::Index J = Eigen::Index(ft_idx.size()), rows = padTo + 2 * J;
	if ((d != 2 && d != 3) || padTo < d || nc < 1 || 2 * nc > K || pose.Gamma.rows() != d ||
	    pose.Gamma.cols() != K || pose.noise.rows() != d || pose.noise.cols() != d)
		throw std::invalid_argument("appendJoinedFeatures: inconsistent sizes");
	checkIndices("appendJoinedFeatures", ft_idx, x.size(), 2);
	ObjectPoseLinearization out;
	out.xi = Eigen::VectorXd::Zero(rows);
	out.xi.head(d) = pose.xi;
	out.idx = pose.idx;
	for (const int k : ft_idx) out.idx.insert(out.idx.end(), {k, k + 1});
	out.Gamma = Eigen::MatrixXd::Zero(rows, K + 2 * J);
	out.Gamma.topLeftCorner(d, K) = pose.Gamma;
	out.noise = Eigen::MatrixXd::Zero(rows, rows);
	out.noise.topLeftCorner(d, d) = pose.noise;
	for (Eigen::Index i = d; i < padTo; ++i) out.noise(i, i) = 1;  // pads
	Eigen::Vector2d c0 = Eigen::Vector2d::Zero();
	for (int k = 0; k < nc; ++k) c0 += x.segment<2>(pose.idx[size_t(2 * k)]) / double(nc);
	std::vector<Eigen::MatrixXd> J_xi;  // d f0_j / d xi
	J_xi.resize(size_t(J));
	for (Eigen::Index j = 0; j < J; ++j)
	{
		const Eigen::Vector2d ft = x.segment<2>(ft_idx[size_t(j)]);
		const Eigen::Index r0 = padTo + 2 * j;
		Eigen::Matrix2d J_ft = Eigen::Matrix2d::Identity();
		if (d == 2)
		{
			out.xi.segment<2>(r0) = ft - pose.xi;
			J_xi[size_t(j)] = -Eigen::Matrix2d::Identity();
		}
		else
		{
			const Eigen::Matrix2d Rt = models::rot2(pose.xi[2]).transpose();
			const Eigen::Vector2d r = ft - c0 - pose.xi.head<2>();
			out.xi.segment<2>(r0) = Rt * r + c0;
			J_xi[size_t(j)].resize(2, 3);
			J_xi[size_t(j)] << -Rt, models::rot2Derivative(pose.xi[2]).transpose() * r;
			J_ft = Rt;
			const Eigen::Matrix2d J_c0 = (Eigen::Matrix2d::Identity() - Rt) / double(nc);
			for (int k = 0; k < nc; ++k) out.Gamma.block<2, 2>(r0, 2 * k) += J_c0;
		}
		out.Gamma.block(r0, 0, 2, K) += J_xi[size_t(j)] * pose.Gamma;
		out.Gamma.block<2, 2>(r0, K + 2 * j) = J_ft;
		out.noise.block(r0, 0, 2, d) = J_xi[size_t(j)] * pose.noise;
		out.noise.block(0, r0, d, 2) = out.noise.block(r0, 0, 2, d).transpose();
		for (Eigen::Index q = 0; q <= j; ++q)
		{
			const Eigen::Matrix2d c = J_xi[size_t(j)] * pose.noise * J_xi[size_t(q)].transpose();
			out.noise.block<2, 2>(r0, padTo + 2 * q) = c;
			out.noise.block<2, 2>(padTo + 2 * q, r0) = c.transpose();
		}
	}
	return out;
}

namespace
{
/** extendedRows (same checks, same values) into a row-major buffer whose storage is reused:
 * row r is contiguous, so the rows of P are plain copies. */
void extendedRowsInto(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                      const std::vector<int>& idx, RowMatrixXd& rows)
{
	const Eigen::Index n = P.rows(), m = a.mean.size();
	if (P.cols() != n || a.cross.rows() != m || a.cross.cols() != n || a.cov.rows() != m ||
	    a.cov.cols() != m)
		throw std::invalid_argument("extendedRows: inconsistent sizes");
	checkIndices("extendedRows", idx, n + m);
	rows.resize(Eigen::Index(idx.size()), n + m);
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
}

/** objectPoseAugmentations' temporaries, kept per thread (no allocation while the sizes do not
 * grow). The product operands have the plain types the expressions of before evaluated into
 * (doc/results/performance.md section 16; test PoseAugmentationExact). */
struct TPoseWorkspace
{
	RowMatrixXd rows;
	Eigen::MatrixXd GammaRows, sub, c, cq;
};
TPoseWorkspace& poseWorkspace()
{
	static thread_local TPoseWorkspace w;
	return w;
}
}  // namespace

Eigen::MatrixXd extendedRows(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                             const std::vector<int>& idx)
{
	RowMatrixXd rows;
	extendedRowsInto(P, a, idx, rows);
	return rows;
}

Augmentation objectPoseAugmentations(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                                     const std::vector<ObjectPoseLinearization>& poses,
                                     const std::vector<Eigen::Index>& at, Eigen::Index size)
{
	const Eigen::Index N = P.rows() + a.mean.size();
	if (at.size() != poses.size())
		throw std::invalid_argument("objectPoseAugmentations: one position per pose");
	for (size_t o = 0; o < poses.size(); ++o)
		if (at[o] < (o == 0 ? 0 : at[o - 1] + poses[o - 1].xi.size()) ||
		    at[o] + poses[o].xi.size() > size)
			throw std::invalid_argument(
			    "objectPoseAugmentations: positions must be ascending, disjoint and in range");
	Augmentation out;
	out.mean = Eigen::VectorXd::Zero(size);
	out.cross = Eigen::MatrixXd::Zero(size, N);
	out.cov = Eigen::MatrixXd::Identity(size, size);  // pads: unit variance
	TPoseWorkspace& w = poseWorkspace();
	for (size_t o = 0; o < poses.size(); ++o)
	{
		const auto& lin = poses[o];
		const Eigen::Index d = lin.xi.size(), r = at[o];
		if (lin.Gamma.rows() != d || lin.Gamma.cols() != Eigen::Index(lin.idx.size()))
			throw std::invalid_argument("objectPoseAugmentations: inconsistent linearization");
		extendedRowsInto(P, a, lin.idx, w.rows);
		out.mean.segment(r, d) = lin.xi;
		// Into a contiguous temporary, then copied: the product zero-fills its destination
		// first, which for these d rows of a column-major matrix was one memset per column.
		w.GammaRows.resize(d, N);
		kernels::productColRow(lin.Gamma.data(), d, lin.Gamma.cols(), w.rows.data(), N,
		                       w.rows.outerStride(), w.GammaRows.data());
		out.cross.middleRows(r, d) = w.GammaRows;
		w.sub = w.rows(Eigen::all, lin.idx);
		w.c = lin.Gamma * w.sub * lin.Gamma.transpose();
		w.c += lin.noise;
		out.cov.block(r, r, d, d) = 0.5 * (w.c + w.c.transpose());
		// with the poses before it: cov(xi_o, xi_q) = cov(xi_o, x_ext)[:, idx_q] Gamma_q^T
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

namespace
{
/** keep = [old (< n) ; a's (n .. n + ma) ; b's], each relative to its group, and the maximal
 * runs of consecutive values in old: (position in old, length). One per thread, its vectors'
 * capacity reused from step to step (no allocation). */
struct TKeepSplit
{
	std::vector<int> old, a, b;
	std::vector<std::pair<Eigen::Index, Eigen::Index>> runs;
};
const TKeepSplit& splitKeep(const char* who, const Eigen::Index n, const Augmentation& a,
                            const Augmentation& b, const std::vector<int>& keep)
{
	const Eigen::Index ma = a.mean.size(), mb = b.mean.size(), k = Eigen::Index(keep.size());
	if (a.cross.rows() != ma || a.cross.cols() != n || a.cov.rows() != ma || a.cov.cols() != ma ||
	    b.cross.rows() != mb || (mb > 0 && b.cross.cols() != n + ma) || b.cov.rows() != mb ||
	    b.cov.cols() != mb)
		throw std::invalid_argument(std::string(who) + ": inconsistent sizes");
	checkIndices(who, keep, n + ma + mb);
	for (Eigen::Index i = 1; i < k; ++i)
		if (keep[i] <= keep[i - 1])
			throw std::invalid_argument(std::string(who) + ": keep must be ascending");
	static thread_local TKeepSplit s;
	s.old.clear();
	s.a.clear();
	s.b.clear();
	s.runs.clear();
	for (const int i : keep)
		(i < n        ? s.old
		 : i < n + ma ? s.a
		              : s.b)
		    .push_back(i < n        ? i
		               : i < n + ma ? i - int(n)
		                            : i - int(n + ma));
	for (size_t i = 0; i < s.old.size();)
	{
		size_t j = i + 1;
		while (j < s.old.size() && s.old[j] == s.old[j - 1] + 1) ++j;
		s.runs.emplace_back(Eigen::Index(i), Eigen::Index(j - i));
		i = j;
	}
	return s;
}

/** Everything of the assembled covariance but its old block (top-left k0 x k0, in place). */
void writeNewEntries(Eigen::Ref<RowMatrixXd> out, const Eigen::Index n, const Augmentation& a,
                     const Augmentation& b, const TKeepSplit& s)
{
	const Eigen::Index k = out.rows(), k0 = Eigen::Index(s.old.size()),
	                   ka = Eigen::Index(s.a.size()), kb = Eigen::Index(s.b.size());
	if (ka > 0)
	{
		out.block(k0, 0, ka, k0) = a.cross(s.a, s.old);
		out.block(k0, k0, ka, ka) = a.cov(s.a, s.a);
	}
	if (kb > 0)
	{
		out.block(k0 + ka, 0, kb, k0) = b.cross(s.b, s.old);
		std::vector<int> kAinB(s.a);
		for (int& i : kAinB) i += int(n);
		out.block(k0 + ka, k0, kb, ka) = b.cross(s.b, kAinB);
		out.block(k0 + ka, k0 + ka, kb, kb) = b.cov(s.b, s.b);
	}
	// upper blocks: transposes of the lower ones
	out.topRightCorner(k0, k - k0) = out.bottomLeftCorner(k - k0, k0).transpose();
	if (ka > 0 && kb > 0)
		out.block(k0, k0 + ka, ka, kb) = out.block(k0 + ka, k0, kb, ka).transpose();
}
}  // namespace

void assembleExtended(const Eigen::Ref<const RowMatrixXd>& P, const Augmentation& a,
                      const Augmentation& b, const std::vector<int>& keep,
                      Eigen::Ref<RowMatrixXd> out)
{
	const Eigen::Index n = P.rows(), k = Eigen::Index(keep.size());
	if (P.cols() != n || out.rows() != k || out.cols() != k)
		throw std::invalid_argument("assembleExtended: inconsistent sizes");
	const TKeepSplit& s = splitKeep("assembleExtended", n, a, b, keep);
	// Old block by runs of consecutive indices (row-major: contiguous copies).
	for (Eigen::Index i = 0; i < Eigen::Index(s.old.size()); ++i)
		for (const auto& [c, len] : s.runs)
			out.row(i).segment(c, len) = P.row(s.old[i]).segment(s.old[c], len);
	writeNewEntries(out, n, a, b, s);
}

void assembleInPlace(double* data, Eigen::Index stride, Eigen::Index n, const Augmentation& a,
                     const Augmentation& b, const std::vector<int>& keep)
{
	const Eigen::Index k = Eigen::Index(keep.size());
	if (!data || n < 0 || n > stride || k > stride)
		throw std::invalid_argument("assembleInPlace: inconsistent sizes");
	const TKeepSplit& s = splitKeep("assembleInPlace", n, a, b, keep);
	// The old block compacted towards the top-left corner, rows ascending and segments
	// ascending: each source lies at or after its destination and after every earlier
	// destination (s.old ascending, s.old[i] >= i), so nothing is read after being overwritten.
	// Rows and segments that do not move (before the first dropped index) are not touched.
	for (Eigen::Index i = 0; i < Eigen::Index(s.old.size()); ++i)
	{
		double* dst = data + i * stride;
		const double* src = data + Eigen::Index(s.old[i]) * stride;
		for (const auto& [c, len] : s.runs)
			if (dst + c != src + s.old[c])
				std::memmove(dst + c, src + s.old[c], size_t(len) * sizeof(double));
	}
	Eigen::Map<RowMatrixXd, Eigen::Unaligned, Eigen::OuterStride<>> out(
	    data, k, k, Eigen::OuterStride<>(stride));
	writeNewEntries(out, n, a, b, s);
}

double sparseUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                    const std::vector<int>& idx, const Eigen::MatrixXd& H,
                    const Eigen::VectorXd& nu, const Eigen::MatrixXd& R)
{
	const Eigen::Index m = H.rows();
	if (H.cols() != Eigen::Index(idx.size()) || nu.size() != m || R.rows() != m || R.cols() != m)
		throw std::invalid_argument("sparseUpdate: inconsistent sizes");
	if (P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("sparseUpdate: P does not match x");
	checkIndices("sparseUpdate", idx, x.size());
	if (m == 0) return 0.0;
	// The arithmetic is a dispatched kernel (dynslam/core/kernels.h: SSE2 or AVX2/FMA variant).
	kernels::TSparseUpdateArgs k;
	k.x = x.data();
	k.P = P.data();
	k.n = P.rows();
	k.ldP = P.outerStride();
	k.idx = idx.data();
	k.k = Eigen::Index(idx.size());
	k.H = H.data();
	k.m = m;
	k.nu = nu.data();
	k.R = R.data();
	double nis = 0;
	if (!kernels::sparseUpdate(k, nis))
		throw std::runtime_error("sparseUpdate: innovation covariance not positive definite");
	return nis;
}

double pseudoMeasurementUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P,
                               const std::vector<int>& base, int d, const PoseResidualFn& residual,
                               const Eigen::MatrixXd& R)
{
	if (d != 2 && d != 3) throw std::invalid_argument("pseudoMeasurementUpdate: d must be 2 or 3");
	checkIndices("pseudoMeasurementUpdate", base, x.size(), d);
	std::vector<Eigen::VectorXd> values;
	std::vector<int> idx;
	for (const int b : base)
	{
		values.push_back(x.segment(b, d));
		for (int i = 0; i < d; ++i) idx.push_back(b + i);
	}
	std::vector<Eigen::MatrixXd> J;
	const Eigen::VectorXd r = residual(values, &J);
	if (J.size() != base.size())
		throw std::invalid_argument("pseudoMeasurementUpdate: one Jacobian per pose needed");
	Eigen::MatrixXd H(r.size(), Eigen::Index(idx.size()));
	for (size_t i = 0; i < J.size(); ++i) H.middleCols(Eigen::Index(i) * d, d) = J[i];
	const double nis = sparseUpdate(x, P, idx, H, -r, R);
	if (d == 3)
		for (const int b : base) x[b + 2] = models::wrapToPi(x[b + 2]);
	return nis;
}

double smoothingUpdate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, int a, int b,
                       int c, const Eigen::MatrixXd& Sigma_s)
{
	const int d = int(Sigma_s.rows());
	if ((d != 2 && d != 3) || Sigma_s.cols() != d)
		throw std::invalid_argument("smoothingUpdate: Sigma_s must be 2x2 or 3x3");
	return pseudoMeasurementUpdate(
	    x, P, {a, b, c}, d,
	    [](const std::vector<Eigen::VectorXd>& v, std::vector<Eigen::MatrixXd>* J)
	    {
		    J->resize(3);
		    return models::smoothingResidual(v[0], v[1], v[2], &(*J)[0], &(*J)[1], &(*J)[2]);
	    },
	    Sigma_s);
}

void propagate(Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, const Eigen::Vector3d& u,
               const Eigen::Matrix3d& Sigma_u, const Eigen::Vector3d* fej_previous_prediction,
               Eigen::Matrix3d* J_out_x_used)
{
	Eigen::Matrix3d F, G;
	x.head<3>() = models::composePose(x.head<3>(), u, &F, &G);
	if (fej_previous_prediction)
	{
		F(0, 2) = -(x[1] - (*fej_previous_prediction)[1]);
		F(1, 2) = x[0] - (*fej_previous_prediction)[0];
	}
	if (J_out_x_used) *J_out_x_used = F;
	const Eigen::Index n = P.rows();
	const Eigen::Matrix3d Pxx = P.topLeftCorner<3, 3>();
	P.topLeftCorner<3, 3>() = F * Pxx * F.transpose() + G * Sigma_u * G.transpose();
	if (n > 3)
	{
		const Eigen::MatrixXd Pxe = F * P.topRightCorner(3, n - 3);
		P.topRightCorner(3, n - 3) = Pxe;
		P.bottomLeftCorner(n - 3, 3) = Pxe.transpose();
	}
}

std::vector<int> keptIndices(int n, const std::vector<int>& remove)
{
	std::vector<bool> drop(n, false);
	for (int r : remove)
	{
		if (r < 0 || r >= n)
			throw std::out_of_range("keptIndices: index " + std::to_string(r) + " out of range");
		drop[r] = true;
	}
	std::vector<int> keep;
	keep.reserve(n);
	for (int i = 0; i < n; ++i)
		if (!drop[i]) keep.push_back(i);
	return keep;
}

Eigen::MatrixXd marginal(const Eigen::Ref<const RowMatrixXd>& P, const std::vector<int>& idx)
{
	if (P.rows() != P.cols()) throw std::invalid_argument("marginal: P is not square");
	checkIndices("marginal", idx, P.rows());
	return P(idx, idx);
}
}  // namespace dynslam::ekf
