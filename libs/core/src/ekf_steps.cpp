#include <dynslam/ekf_steps.h>
#include <dynslam/models/object_pose.h>
#include <dynslam/models/se2.h>
#include <dynslam/models/smoothing.h>

#include <Eigen/Cholesky>
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
			throw std::out_of_range(
				std::string(fn) + ": state index " + std::to_string(i) + " out of range for " +
				std::to_string(width) + " entries in a state of size " + std::to_string(n));
}
}  // namespace

Augmentation featureAugmentation(
	models::MeasurementModel model, const Eigen::Vector3d& ego,
	const Eigen::Ref<const RowMatrixXd>& P_ego_rows, const std::vector<Eigen::Vector2d>& z,
	const Eigen::Matrix2d& R)
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
		a.mean.segment<2>(2 * i) = models::inverseObserve(model, ego, z[i], &Lx[i], &Lz);
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

Augmentation objectPoseAugmentation(
	const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const RowMatrixXd>& P,
	const std::vector<int>& f0_idx, const std::vector<int>& ft_idx, const std::vector<int>& seen,
	const Eigen::Matrix2d& Sigma_xi)
{
	const int n = int(f0_idx.size()), m = int(ft_idx.size());
	if (n < 1 || m < 1) throw std::invalid_argument("objectPoseAugmentation: no features");
	if (P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("objectPoseAugmentation: P does not match x");
	checkIndices("objectPoseAugmentation", f0_idx, x.size(), 2);
	checkIndices("objectPoseAugmentation", ft_idx, x.size(), 2);
	if (n == 1 && (m != 1 || (!seen.empty() && (seen.size() != 1 || seen[0] != 0))))
		throw std::invalid_argument(
			"objectPoseAugmentation: a one-feature object needs exactly that feature at time t");
	Eigen::Matrix2Xd f0(2, n), ft(2, m);
	for (int k = 0; k < n; ++k) f0.col(k) = x.segment<2>(f0_idx[k]);
	for (int i = 0; i < m; ++i) ft.col(i) = x.segment<2>(ft_idx[i]);

	Eigen::MatrixXd G1, G2;
	Eigen::VectorXd xi;
	if (n == 1)
	{
		Eigen::Matrix2d g1, g2;
		xi = models::objectTranslationInverse(f0.col(0), ft.col(0), &g1, &g2);
		G1 = g1;
		G2 = g2;
	}
	else
		xi = models::objectPoseInverse(f0, ft, seen, &G1, &G2);

	// Gamma = [Gamma1 Gamma2] over the stacked indices [f0 ; ft]
	std::vector<int> idx;
	idx.reserve(2 * (n + m));
	for (int k : f0_idx) idx.insert(idx.end(), {k, k + 1});
	for (int k : ft_idx) idx.insert(idx.end(), {k, k + 1});
	Eigen::MatrixXd Gamma(xi.size(), 2 * (n + m));
	Gamma << G1, G2;

	Augmentation a;
	a.mean = xi;
	a.cross.noalias() = Gamma * P(idx, Eigen::all);
	a.cov.noalias() = Gamma * P(idx, idx) * Gamma.transpose();
	for (int i = 0; i < m; ++i)
		a.cov.noalias() += G2.middleCols<2>(2 * i) * Sigma_xi * G2.middleCols<2>(2 * i).transpose();
	a.cov = 0.5 * (a.cov + a.cov.transpose()).eval();
	return a;
}

double sparseUpdate(
	Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, const std::vector<int>& idx,
	const Eigen::MatrixXd& H, const Eigen::VectorXd& nu, const Eigen::MatrixXd& R)
{
	const Eigen::Index m = H.rows();
	if (H.cols() != Eigen::Index(idx.size()) || nu.size() != m || R.rows() != m || R.cols() != m)
		throw std::invalid_argument("sparseUpdate: inconsistent sizes");
	if (P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("sparseUpdate: P does not match x");
	checkIndices("sparseUpdate", idx, x.size());
	if (m == 0) return 0.0;
	const Eigen::MatrixXd PHt = P(Eigen::all, idx) * H.transpose();  // n x m
	Eigen::MatrixXd S = H * PHt(idx, Eigen::all) + R;
	S = 0.5 * (S + S.transpose()).eval();
	const Eigen::LLT<Eigen::MatrixXd> llt(S);
	if (llt.info() != Eigen::Success)
		throw std::runtime_error("sparseUpdate: innovation covariance not positive definite");
	const Eigen::MatrixXd K = llt.solve(PHt.transpose()).transpose();  // n x m
	x.noalias() += K * nu;
	P.noalias() -= K * PHt.transpose();  // = K S K^T
	P = 0.5 * (P + P.transpose()).eval();
	return nu.dot(llt.solve(nu));
}

double smoothingUpdate(
	Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, int a, int b, int c,
	const Eigen::MatrixXd& Sigma_s)
{
	const int d = int(Sigma_s.rows());
	if ((d != 2 && d != 3) || Sigma_s.cols() != d)
		throw std::invalid_argument("smoothingUpdate: Sigma_s must be 2x2 or 3x3");
	checkIndices("smoothingUpdate", {a, b, c}, x.size(), d);
	Eigen::MatrixXd Ja, Jb, Jc;
	const Eigen::VectorXd s = models::smoothingResidual(
		x.segment(a, d), x.segment(b, d), x.segment(c, d), &Ja, &Jb, &Jc);
	std::vector<int> idx;
	for (int base : {a, b, c})
		for (int i = 0; i < d; ++i) idx.push_back(base + i);
	Eigen::MatrixXd H(d, 3 * d);
	H << Ja, Jb, Jc;
	const double nis = sparseUpdate(x, P, idx, H, -s, Sigma_s);
	if (d == 3)
		for (int base : {a, b, c}) x[base + 2] = models::wrapToPi(x[base + 2]);
	return nis;
}

void propagate(
	Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<RowMatrixXd> P, const Eigen::Vector3d& u,
	const Eigen::Matrix3d& Sigma_u)
{
	Eigen::Matrix3d F, G;
	x.head<3>() = models::composePose(x.head<3>(), u, &F, &G);
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
