// SE(2) trajectory alignment (align.h) and the aligned ATE of computeRunMetrics.
#include <dynslam/eval/align.h>
#include <dynslam/eval/metrics.h>
#include <gtest/gtest.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/tfest/se2.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

using namespace dynslam;
using namespace dynslam::eval;

namespace
{
std::vector<Eigen::Vector2d> curvyPath(size_t n)
{
	std::vector<Eigen::Vector2d> p;
	for (size_t i = 0; i < n; ++i)
	{
		const double s = 0.1 * static_cast<double>(i);
		p.emplace_back(3 * std::cos(s) + 0.2 * s, 2 * std::sin(1.3 * s));
	}
	return p;
}
std::vector<Eigen::Vector2d> transform(const std::vector<Eigen::Vector2d>& p, double th,
                                       const Eigen::Vector2d& t)
{
	std::vector<Eigen::Vector2d> out;
	for (const auto& x : p) out.push_back(Eigen::Rotation2Dd(th) * x + t);
	return out;
}
double rmsAfter(const std::vector<Eigen::Vector2d>& est, const std::vector<Eigen::Vector2d>& tr,
                double th, const Eigen::Vector2d& t)
{
	double s = 0;
	for (size_t i = 0; i < est.size(); ++i)
		s += (tr[i] - (Eigen::Rotation2Dd(th) * est[i] + t)).squaredNorm();
	return std::sqrt(s / static_cast<double>(est.size()));
}
}  // namespace

TEST(Align, RecoversARigidTransformExactly)
{
	const auto truth = curvyPath(80);
	// est = inverse transform of the truth, so the alignment is (0.7 rad, (1.5, -2)).
	const double th = 0.7;
	const Eigen::Vector2d t(1.5, -2.0);
	std::vector<Eigen::Vector2d> est;
	for (const auto& x : truth) est.push_back(Eigen::Rotation2Dd(-th) * (x - t));
	const auto a = alignSE2(est, truth);
	EXPECT_NEAR(a.q[0], 1.5, 1e-12);
	EXPECT_NEAR(a.q[1], -2.0, 1e-12);
	EXPECT_NEAR(a.q[2], 0.7, 1e-12);
	EXPECT_LT(a.rms, 1e-12);
}

TEST(Align, NoisyCaseMatchesMrptSe2L2AndABruteForceMinimum)
{
	std::mt19937 rng(17);
	std::normal_distribution<double> n(0, 0.15);
	const auto truth = curvyPath(60);
	auto est = transform(truth, -0.4, Eigen::Vector2d(0.3, 0.8));
	for (auto& p : est) p += Eigen::Vector2d(n(rng), n(rng));
	const auto a = alignSE2(est, truth);

	// MRPT: p_global (truth) = q (+) p_local (est).
	mrpt::tfest::TMatchingPairList pairs;
	for (size_t i = 0; i < est.size(); ++i)
		pairs.emplace_back(static_cast<uint32_t>(i), static_cast<uint32_t>(i),
		                   static_cast<float>(truth[i].x()), static_cast<float>(truth[i].y()), 0.f,
		                   static_cast<float>(est[i].x()), static_cast<float>(est[i].y()), 0.f);
	mrpt::math::TPose2D q;
	ASSERT_TRUE(mrpt::tfest::se2_l2(pairs, q));
	EXPECT_NEAR(a.q[0], q.x, 1e-4);  // MRPT's pairs are float
	EXPECT_NEAR(a.q[1], q.y, 1e-4);
	EXPECT_NEAR(a.q[2], q.phi, 1e-5);

	// Brute force: no transform on a grid around the solution does better.
	EXPECT_NEAR(a.rms, rmsAfter(est, truth, a.q[2], a.q.head<2>()), 1e-12);
	for (int i = -3; i <= 3; ++i)
		for (int j = -3; j <= 3; ++j)
			for (int k = -3; k <= 3; ++k)
			{
				if (i == 0 && j == 0 && k == 0) continue;
				const double r = rmsAfter(est, truth, a.q[2] + 1e-3 * k,
				                          a.q.head<2>() + Eigen::Vector2d(1e-3 * i, 1e-3 * j));
				EXPECT_GT(r, a.rms) << i << " " << j << " " << k;
			}
	EXPECT_GT(a.rms, 0.1);  // the noise stays: ~0.15 sqrt(2) minus the 3 fitted dof
	EXPECT_LT(a.rms, 0.3);
}

TEST(Align, BadInputAndOnePoint)
{
	EXPECT_THROW(alignSE2({}, {}), std::invalid_argument);
	EXPECT_THROW(alignSE2({Eigen::Vector2d(0, 0)}, {}), std::invalid_argument);
	const auto a = alignSE2({Eigen::Vector2d(1, 2)}, {Eigen::Vector2d(4, 0)});
	EXPECT_NEAR(a.q[0], 3, 1e-15);
	EXPECT_NEAR(a.q[1], -2, 1e-15);
	EXPECT_EQ(a.q[2], 0);
	EXPECT_LT(a.rms, 1e-15);
}

TEST(Align, RunMetricsAlignedAteOfAWholeRotatedTrajectory)
{
	const auto truth = curvyPath(50);
	io::TGroundTruth gt;
	TRunEstimates est;
	const auto moved = transform(truth, 0.3, Eigen::Vector2d(2, -1));
	for (size_t k = 0; k < truth.size(); ++k)
	{
		gt.ego.emplace_back(truth[k].x(), truth[k].y(), 0.1 * static_cast<double>(k));
		TEgoEstimate e;
		e.step = static_cast<int>(k);
		e.mean << moved[k].x(), moved[k].y(), 0.1 * static_cast<double>(k) + 0.3;
		e.cov = Eigen::Matrix3d::Identity();
		est.ego.push_back(e);
	}
	const auto m = computeRunMetrics(gt, est);
	EXPECT_GT(m.ate, 1.0);
	EXPECT_LT(m.ate_aligned, 1e-12);
	// A wrong (not rigidly moved) trajectory keeps a large aligned ATE.
	for (size_t k = 0; k < truth.size(); k += 2) est.ego[k].mean[0] += 1.0;
	const auto w = computeRunMetrics(gt, est);
	EXPECT_GT(w.ate_aligned, 0.4);
	EXPECT_LE(w.ate_aligned, w.ate);
}
