#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynslam::models
{
Eigen::Matrix2Xd objectPoseMap(const Eigen::Vector3d& xi, const Eigen::Matrix2Xd& f0,
                               Eigen::MatrixXd* J_ft_xi, Eigen::MatrixXd* J_ft_f0, int centroidCols)
{
	const Eigen::Index n = f0.cols();
	if (n < 1) throw std::invalid_argument("objectPoseMap: object without features");
	if (centroidCols < 0 || centroidCols > n)
		throw std::invalid_argument("objectPoseMap: centroidCols not in [0, n]");
	const Eigen::Index nc = centroidCols == 0 ? n : centroidCols;
	const Eigen::Vector2d c0 = f0.leftCols(nc).rowwise().mean();
	const Eigen::Matrix2d R = rot2(xi[2]), dR = rot2Derivative(xi[2]);
	Eigen::Matrix2Xd ft(2, n);
	for (Eigen::Index k = 0; k < n; ++k) ft.col(k) = R * (f0.col(k) - c0) + c0 + xi.head<2>();
	if (J_ft_xi)
	{
		J_ft_xi->resize(2 * n, 3);
		for (Eigen::Index k = 0; k < n; ++k)
		{
			J_ft_xi->block<2, 2>(2 * k, 0).setIdentity();
			J_ft_xi->block<2, 1>(2 * k, 2) = dR * (f0.col(k) - c0);
		}
	}
	if (J_ft_f0)
	{
		// d ft_k / d f0_j = R delta_kj + (I - R) / nc (j < nc: a centroid column)
		const Eigen::Matrix2d common = (Eigen::Matrix2d::Identity() - R) / double(nc);
		J_ft_f0->resize(2 * n, 2 * n);
		for (Eigen::Index k = 0; k < n; ++k)
			for (Eigen::Index j = 0; j < n; ++j)
				J_ft_f0->block<2, 2>(2 * k, 2 * j) = (j < nc ? common : Eigen::Matrix2d::Zero()) +
				                                     (k == j ? R : Eigen::Matrix2d::Zero());
	}
	return ft;
}

namespace
{
/** objectPoseInverse's correspondence list: seenIn (time-0 index of each of the m time-t
 * features; empty: the identity when m == n), checked to be m distinct indices below n. */
std::vector<int> checkedCorrespondences(Eigen::Index n, Eigen::Index m,
                                        const std::vector<int>& seenIn)
{
	std::vector<int> seen = seenIn;
	if (seen.empty())
	{
		if (m != n)
			throw std::invalid_argument("objectPoseInverse: " + std::to_string(m) +
			                            " time-t features for " + std::to_string(n) +
			                            " time-0 features and no correspondence list");
		for (int i = 0; i < n; ++i) seen.push_back(i);
	}
	if (Eigen::Index(seen.size()) != m)
		throw std::invalid_argument("objectPoseInverse: correspondence list size mismatch");
	std::vector<bool> used(n, false);
	for (int s : seen)
	{
		if (s < 0 || s >= n || used[s])
			throw std::invalid_argument("objectPoseInverse: bad or duplicate correspondence " +
			                            std::to_string(s));
		used[s] = true;
	}
	return seen;
}
}  // namespace

Eigen::Vector3d objectPoseInverse(const Eigen::Matrix2Xd& f0, const Eigen::Matrix2Xd& ft,
                                  const std::vector<int>& seenIn, Eigen::MatrixXd* Gamma1,
                                  Eigen::MatrixXd* Gamma2, int centroidCols)
{
	const Eigen::Index n = f0.cols(), m = ft.cols();
	const std::vector<int> seen = checkedCorrespondences(n, m, seenIn);
	if (centroidCols < 0 || centroidCols > n)
		throw std::invalid_argument(
		    "objectPoseInverse: centroidCols = " + std::to_string(centroidCols) + " not in [0, n]");
	const Eigen::Index nc = centroidCols == 0 ? n : centroidCols;
	if (m < 2)
		throw std::domain_error("objectPoseInverse: rotation undetermined with " +
		                        std::to_string(m) + " seen feature(s)");

	const Eigen::Vector2d c0 = f0.leftCols(nc).rowwise().mean();
	Eigen::Matrix2Xd a(2, m);
	for (Eigen::Index i = 0; i < m; ++i) a.col(i) = f0.col(seen[i]);
	const Eigen::Vector2d abar = a.rowwise().mean(), bbar = ft.rowwise().mean();
	const Eigen::Matrix2Xd p = a.colwise() - abar, q = ft.colwise() - bbar;
	double S = 0, C = 0;
	for (Eigen::Index i = 0; i < m; ++i)
	{
		S += p.col(i).dot(q.col(i));
		C += p(0, i) * q(1, i) - p(1, i) * q(0, i);
	}
	const double pp = p.squaredNorm(), qq = q.squaredNorm(), D = S * S + C * C;
	// Coinciding features leave only rounding noise in the centred points (the centroid of
	// identical values is not always exactly that value), and noise at both times passes the
	// D test below with an arbitrary rotation. So an RMS spread below 1e-12 of the coordinates'
	// magnitude counts as zero (the noise is ~m * eps * magnitude).
	const double spreadTol = 1e-12 * std::max(a.cwiseAbs().maxCoeff(), ft.cwiseAbs().maxCoeff());
	const double minSpread2 = double(m) * spreadTol * spreadTol;
	// By Cauchy-Schwarz D <= pp*qq; D ~ pp*qq for a rigid motion. Coinciding points give 0.
	if (!(pp > minSpread2) || !(qq > minSpread2) || !(D > 1e-20 * pp * qq) || !std::isfinite(D))
		throw std::domain_error("objectPoseInverse: seen features coincide, rotation undetermined");

	// atan2 returns -pi for (C, S) = (-0, S < 0): wrap into (-pi, pi] like every other angle
	const double th = wrapToPi(std::atan2(C, S));
	const Eigen::Matrix2d R = rot2(th), dR = rot2Derivative(th);
	const Eigen::Vector2d lever = abar - c0;
	Eigen::Vector3d xi;
	xi.head<2>() = bbar - R * lever - c0;
	xi[2] = th;

	if (Gamma1 || Gamma2)
	{
		const Eigen::Vector2d dRlever = dR * lever;
		// d theta / d b_i and d theta / d a_i (the centring terms cancel since sum p = sum q = 0)
		Eigen::Matrix2Xd dth_db(2, m), dth_da(2, m);
		for (Eigen::Index i = 0; i < m; ++i)
		{
			const Eigen::Vector2d pi = p.col(i), qi = q.col(i);
			dth_db.col(i) = (S * Eigen::Vector2d(-pi[1], pi[0]) - C * pi) / D;
			dth_da.col(i) = (S * Eigen::Vector2d(qi[1], -qi[0]) - C * qi) / D;
		}
		if (Gamma2)
		{
			Gamma2->setZero(3, 2 * m);
			for (Eigen::Index i = 0; i < m; ++i)
			{
				Gamma2->block<2, 2>(0, 2 * i) =
				    Eigen::Matrix2d::Identity() / double(m) - dRlever * dth_db.col(i).transpose();
				Gamma2->block<1, 2>(2, 2 * i) = dth_db.col(i).transpose();
			}
		}
		if (Gamma1)
		{
			Gamma1->setZero(3, 2 * n);
			const Eigen::Matrix2d In = Eigen::Matrix2d::Identity() / double(nc);
			// c0 terms, common to every centroid column: -R (-I/nc) - I/nc = (R - I)/nc
			for (Eigen::Index k = 0; k < nc; ++k) Gamma1->block<2, 2>(0, 2 * k) = R * In - In;
			for (Eigen::Index i = 0; i < m; ++i)
			{
				const int k = seen[i];
				Gamma1->block<2, 2>(0, 2 * k) +=
				    -R / double(m) - dRlever * dth_da.col(i).transpose();
				Gamma1->block<1, 2>(2, 2 * k) = dth_da.col(i).transpose();
			}
		}
	}
	return xi;
}

Eigen::Vector2d objectTranslationInverse(const Eigen::Vector2d& f0, const Eigen::Vector2d& ft,
                                         Eigen::Matrix2d* Gamma1, Eigen::Matrix2d* Gamma2)
{
	if (Gamma1) *Gamma1 = -Eigen::Matrix2d::Identity();
	if (Gamma2) *Gamma2 = Eigen::Matrix2d::Identity();
	return ft - f0;
}
}  // namespace dynslam::models
