/** Noise estimation: the statistics and the odometry fit recover known parameters from
 * seeded synthetic samples. */
#include <dynslam/mrclam/noise_estimation.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace dynslam::mrclam;

TEST(MrclamNoise, ResidualStatsRobustToOutliers)
{
	std::mt19937 rng(42);
	std::normal_distribution<double> g(0.02, 0.1);
	std::uniform_real_distribution<double> u(-5.0, 5.0);
	std::vector<double> r;
	for (int i = 0; i < 20000; i++) r.push_back(i % 50 == 0 ? 3.0 + std::abs(u(rng)) : g(rng));
	const auto s = residualStats(r, 5.0);
	EXPECT_EQ(s.n, 20000u);
	EXPECT_NEAR(s.median, 0.02, 0.005);
	EXPECT_NEAR(s.robust_std, 0.1, 0.005);
	EXPECT_NEAR(s.outlier_fraction, 0.02, 0.002);  // 1 in 50 injected, all beyond 5 sigma
	EXPECT_NEAR(s.inlier_mean, 0.02, 0.005);
	EXPECT_NEAR(s.inlier_std, 0.1, 0.005);
	EXPECT_GT(s.std, 0.4);  // the plain std is ruined by the outliers
	EXPECT_EQ(residualStats({}, 5.0).n, 0u);
}

TEST(MrclamNoise, OdometryFitRecoversTheModel)
{
	TOdometryNoiseModel truth;
	truth.std_xy_min = 0.002;
	truth.var_xy_per_m = 2e-4;
	truth.var_xy_per_rad = 1.5e-4;
	truth.std_phi_min = 0.003;
	truth.var_phi_per_m = 1.7e-3;
	truth.var_phi_per_rad = 7e-3;
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> ud(0.0, 0.1), ua(0.0, 0.3);
	std::normal_distribution<double> n01(0.0, 1.0);
	TNoiseSamples s;
	for (int i = 0; i < 20000; i++)
	{
		TOdometryIncrement inc;
		// one step in five without motion (as while a robot stands still): identifies the floors
		inc.distance = i % 5 == 1 ? 0.0 : ud(rng);
		inc.angle = i % 5 == 1 ? 0.0 : ua(rng);
		const Eigen::Matrix3d C = truth.covariance(inc);
		TNoiseSamples::TOdo o;
		o.ego = 1;
		o.distance = inc.distance;
		o.angle = inc.angle;
		o.odo = Eigen::Vector3d(inc.distance, 0, inc.angle);
		o.e = Eigen::Vector3d(std::sqrt(C(0, 0)) * n01(rng), std::sqrt(C(1, 1)) * n01(rng),
		                      std::sqrt(C(2, 2)) * n01(rng));
		if (i % 200 == 0) o.e *= 30.0;  // gross outliers (0.5%)
		o.gt = o.odo + o.e;
		s.odo.push_back(o);
	}
	const auto est = estimateNoise(s);
	const auto& m = est.odometry;
	EXPECT_NEAR(m.std_xy_min, truth.std_xy_min, 0.05 * truth.std_xy_min);
	EXPECT_NEAR(m.std_phi_min, truth.std_phi_min, 0.05 * truth.std_phi_min);
	EXPECT_NEAR(m.var_xy_per_m, truth.var_xy_per_m, 0.15 * truth.var_xy_per_m);
	EXPECT_NEAR(m.var_xy_per_rad, truth.var_xy_per_rad, 0.15 * truth.var_xy_per_rad);
	EXPECT_NEAR(m.var_phi_per_m, truth.var_phi_per_m, 0.15 * truth.var_phi_per_m);
	EXPECT_NEAR(m.var_phi_per_rad, truth.var_phi_per_rad, 0.15 * truth.var_phi_per_rad);
	// predicted variances over the sampled range within 5 %
	for (double d : {0.0, 0.05, 0.1})
		for (double a : {0.0, 0.15, 0.3})
		{
			TOdometryIncrement inc;
			inc.distance = d;
			inc.angle = a;
			const Eigen::Matrix3d Ct = truth.covariance(inc), Ce = m.covariance(inc);
			EXPECT_NEAR(Ce(0, 0), Ct(0, 0), 0.05 * Ct(0, 0)) << d << " " << a;
			EXPECT_NEAR(Ce(2, 2), Ct(2, 2), 0.05 * Ct(2, 2)) << d << " " << a;
		}
	EXPECT_NEAR(est.odo_trimmed_fraction_xy, 0.005, 0.003);
	EXPECT_NEAR(est.odo_frac_phi_above_95, 0.05, 0.01);
	EXPECT_EQ(est.odo_steps, 20000u);
}
