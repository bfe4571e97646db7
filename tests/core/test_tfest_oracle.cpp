/** gamma (objectPoseInverse) vs MRPT's closed-form rigid 2-D fit mrpt::tfest::se2_l2 on
 * noise-free data.
 *
 * MRPT's convention: p_global = q (+) p_local, i.e. b = R(phi) a + t with a the time-0
 * features (local) and b the time-t features (global). Our xi rotates about the centroid c0 of
 * all time-0 features: b = R(dtheta) (a - c0) + c0 + (dx, dy). Hence dtheta = phi and
 * (dx, dy) = t + R(phi) c0 - c0 (c0 = abar when every feature is seen).
 *
 * TMatchingPairList stores float, so both sides get the same float-rounded points and the
 * tolerance is a float one: 1e-4 (rad, and m relative to the coordinates' magnitude).
 * se2_l2 also accumulates uncentred sums in float (N Sxx - SumXa SumXb), which cancels
 * catastrophically for objects far from the origin (observed: 3e-4 rad error for 1-5 m objects
 * 30 m away; ours is exact on the same data). So the oracle is used (a) directly on objects
 * near the origin, and (b) on far objects through centred copies a - abar, b - bbar, with
 * t = t' + bbar - R abar. */
#include <dynslam/core/models/object_pose.h>
#include <dynslam/core/models/se2.h>
#include <gtest/gtest.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/tfest/se2.h>

#include <algorithm>
#include <numeric>

#include "core_test_utils.h"

using namespace dynslam::models;
using dynslam_test::uniform;

namespace
{
constexpr double kFloatTol = 1e-4;

/** Float-rounded copy: what TMatchingPairList stores. */
Eigen::Matrix2Xd toFloat(const Eigen::Matrix2Xd& F) { return F.cast<float>().cast<double>(); }

/** se2_l2 on (a -> b) pairs, converted to our xi with the rotation centre c0. With `centred`,
 * MRPT gets a - abar and b - bbar (each rounded to float), and t is moved back. */
Eigen::Vector3d mrptXi(const Eigen::Matrix2Xd& a, const Eigen::Matrix2Xd& b,
                       const Eigen::Vector2d& c0, bool centred)
{
	const Eigen::Vector2d sa =
	    centred ? Eigen::Vector2d(a.rowwise().mean()) : Eigen::Vector2d::Zero();
	const Eigen::Vector2d sb =
	    centred ? Eigen::Vector2d(b.rowwise().mean()) : Eigen::Vector2d::Zero();
	mrpt::tfest::TMatchingPairList pairs;
	for (Eigen::Index i = 0; i < a.cols(); ++i)
		pairs.emplace_back(uint32_t(i), uint32_t(i), float(b(0, i) - sb[0]), float(b(1, i) - sb[1]),
		                   0.f, float(a(0, i) - sa[0]), float(a(1, i) - sa[1]), 0.f);
	mrpt::math::TPose2D q;
	EXPECT_TRUE(mrpt::tfest::se2_l2(pairs, q));
	const Eigen::Matrix2d R = rot2(q.phi);
	const Eigen::Vector2d t = Eigen::Vector2d(q.x, q.y) + sb - R * sa;
	Eigen::Vector3d xi;
	xi.head<2>() = t + R * c0 - c0;
	xi[2] = q.phi;
	return xi;
}

/** Random well-spread object (features on a jittered circle of radius 1-5 m, so no two nearly
 * coincide: se2_l2's float sums lose ~eps_float (|coordinate| / spread)^2), centred near the
 * origin (in [-3, 3]^2) or anywhere in [-30, 30]^2. */
Eigen::Matrix2Xd randomObject(int n, bool nearOrigin)
{
	const double lim = nearOrigin ? 3 : 30;
	const Eigen::Vector2d c = core_test::randomVector(2, -lim, lim);
	const double r = uniform(1, 5), phi = uniform(-M_PI, M_PI);
	Eigen::Matrix2Xd F(2, n);
	for (int k = 0; k < n; ++k)
	{
		const double a = phi + 2 * M_PI * (k + uniform(-0.3, 0.3)) / n;
		F.col(k) = c + r * uniform(0.7, 1.0) * Eigen::Vector2d(std::cos(a), std::sin(a));
	}
	return F;
}

double poseError(const Eigen::Vector3d& ours, const Eigen::Vector3d& ref, double scale)
{
	return std::max((ours.head<2>() - ref.head<2>()).norm() / std::max(1.0, scale),
	                std::abs(wrapToPi(ours[2] - ref[2])));
}

std::vector<double> angles()
{
	std::vector<double> a;
	for (int i = 0; i < 20; ++i) a.push_back(uniform(-M_PI, M_PI));
	for (double th : core_test::wrapHeadings()) a.push_back(th);
	return a;
}
}  // namespace

TEST(GammaVsTfest, AllSeen)
{
	dynslam_test::rng(401);
	double worst = 0;
	for (bool far : {false, true})
		for (int n = 2; n <= 8; ++n)
			for (double dth : angles())
			{
				const Eigen::Matrix2Xd f0 = toFloat(randomObject(n, !far));
				const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
				const Eigen::Matrix2Xd ft = toFloat(objectPoseMap(xi, f0));
				const Eigen::Vector3d ours = objectPoseInverse(f0, ft);
				const Eigen::Vector3d ref = mrptXi(f0, ft, f0.rowwise().mean(), far);
				const double scale = std::max(f0.cwiseAbs().maxCoeff(), ft.cwiseAbs().maxCoeff());
				const double e = poseError(ours, ref, scale);
				EXPECT_LE(e, kFloatTol)
				    << (far ? "far" : "near") << ", n = " << n << "\nours " << ours.transpose()
				    << "\nmrpt " << ref.transpose() << "\ntrue " << xi.transpose();
				worst = std::max(worst, e);
			}
	core_test::reportWorst("gamma vs se2_l2, all seen", worst);
}

TEST(GammaVsTfest, SubsetSeen)
{
	dynslam_test::rng(402);
	double worst = 0;
	for (bool far : {false, true})
		for (int n = 3; n <= 8; ++n)
			for (double dth : angles())
			{
				const Eigen::Matrix2Xd f0 = toFloat(randomObject(n, !far));
				const Eigen::Vector3d xi(uniform(-10, 10), uniform(-10, 10), dth);
				const Eigen::Matrix2Xd ftAll = toFloat(objectPoseMap(xi, f0));
				std::vector<int> seen(size_t(n), 0);
				std::iota(seen.begin(), seen.end(), 0);
				std::shuffle(seen.begin(), seen.end(), dynslam_test::rng());
				seen.resize(size_t(2 + int(dynslam_test::rng()() % unsigned(n - 2))));
				const int m = int(seen.size());
				Eigen::Matrix2Xd a(2, m), b(2, m);
				for (int i = 0; i < m; ++i)
				{
					a.col(i) = f0.col(seen[size_t(i)]);
					b.col(i) = ftAll.col(seen[size_t(i)]);
				}
				const Eigen::Vector3d ours = objectPoseInverse(f0, b, seen);
				// MRPT fits the seen pairs only; the rotation centre stays the all-feature centroid
				const Eigen::Vector3d ref = mrptXi(a, b, f0.rowwise().mean(), far);
				const double scale = std::max(f0.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
				const double e = poseError(ours, ref, scale);
				EXPECT_LE(e, kFloatTol) << (far ? "far" : "near") << ", n = " << n << ", m = " << m;
				worst = std::max(worst, e);
			}
	core_test::reportWorst("gamma vs se2_l2, subset seen", worst);
}
