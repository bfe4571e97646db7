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

namespace
{
/** n samples of a zero-mean AR(1) process x_k = phi x_{k-1} + w_k with unit variance. */
std::vector<double> ar1(std::mt19937& rng, double phi, size_t n)
{
	std::normal_distribution<double> g(0.0, 1.0);
	std::vector<double> x(n);
	double v = g(rng);
	for (auto& xi : x)
	{
		v = phi * v + std::sqrt(1 - phi * phi) * g(rng);
		xi = v;
	}
	return x;
}
}  // namespace

TEST(MrclamNoise, IntegratedAutocorrelationOfAr1AndWhiteNoise)
{
	// AR(1): rho(l) = phi^l, tau = (1 + phi) / (1 - phi) = 9 for phi = 0.8
	std::mt19937 rng(11);
	std::vector<std::vector<double>> s;
	for (int i = 0; i < 5; i++) s.push_back(ar1(rng, 0.8, 20000));
	const auto a = integratedAutocorrelation(s);
	EXPECT_TRUE(a.converged);
	EXPECT_NEAR(a.tau, 9.0, 0.9);
	EXPECT_NEAR(a.rho.at(1), 0.8, 0.02);
	EXPECT_GE(a.window, 5 * a.tau - 1);
	EXPECT_EQ(a.n, 100000u);
	std::vector<std::vector<double>> w{ar1(rng, 0.0, 50000)};
	EXPECT_NEAR(integratedAutocorrelation(w).tau, 1.0, 0.1);
	// a constant offset is correlation (no mean is removed): tau grows to the window
	std::vector<std::vector<double>> b{std::vector<double>(1000, 0.5)};
	EXPECT_FALSE(integratedAutocorrelation(b, 5, 50).converged);
	EXPECT_GT(integratedAutocorrelation(b, 5, 50).tau, 90);
	// no data: tau = 1; bad parameters throw
	EXPECT_EQ(integratedAutocorrelation({}).tau, 1.0);
	EXPECT_THROW(integratedAutocorrelation(s, 0), std::invalid_argument);
	EXPECT_THROW(integratedAutocorrelation(s, 5, 0), std::invalid_argument);
}

TEST(MrclamNoise, OdometryCorrelationGivesTheInflation)
{
	// heading errors AR(1) with phi = 0.8 (tau 9), x/y errors AR(1) with phi = 0.5 (tau 3), two
	// robots; the fit still finds the per-step variances, and the taus are the inflations
	TOdometryNoiseModel truth;
	truth.std_xy_min = 0.002;
	truth.var_xy_per_m = 2e-4;
	truth.std_phi_min = 0.003;
	truth.var_phi_per_rad = 7e-3;
	std::mt19937 rng(5);
	std::uniform_real_distribution<double> ud(0.0, 0.1), ua(0.0, 0.3);
	TNoiseSamples s;
	for (int ego : {1, 2})
	{
		const auto zx = ar1(rng, 0.5, 20000), zy = ar1(rng, 0.5, 20000), zp = ar1(rng, 0.8, 20000);
		for (size_t i = 0; i < zx.size(); i++)
		{
			TNoiseSamples::TOdo o;
			o.ego = ego;
			o.distance = ud(rng);
			o.angle = ua(rng);
			TOdometryIncrement inc;
			inc.distance = o.distance;
			inc.angle = o.angle;
			const Eigen::Vector3d sd = truth.covariance(inc).diagonal().cwiseSqrt();
			o.odo = Eigen::Vector3d(o.distance, 0, o.angle);
			o.e = Eigen::Vector3d(sd.x() * zx[i], sd.y() * zy[i], sd.z() * zp[i]);
			o.gt = o.odo + o.e;
			s.odo.push_back(o);
		}
	}
	const auto est = estimateNoise(s);
	EXPECT_NEAR(est.odometry.var_phi_per_rad, truth.var_phi_per_rad, 0.1 * truth.var_phi_per_rad);
	EXPECT_NEAR(est.odometry.tau_phi, 9.0, 0.9);
	EXPECT_NEAR(est.odometry.tau_xy, 3.0, 0.3);
	EXPECT_EQ(est.odometry.model, TOdometryNoiseModel::Model::white);  // the fit itself
	// sums of 100 steps: the white model's NEES per dof is about tau (slightly less: the window
	// is not much longer than the correlation), 1 for single steps
	ASSERT_EQ(est.odo_window_lengths.at(0), 1);
	ASSERT_EQ(est.odo_window_lengths.at(3), 100);
	EXPECT_NEAR(est.odo_window_nees_phi.at(0), 1.0, 0.1);
	EXPECT_NEAR(est.odo_window_nees_phi.at(3), 9.0 * (1 - 0.08), 1.5);
	EXPECT_NEAR(est.odo_window_nees_xy.at(3), 3.0, 0.5);
	// the INI lines carry the inflated model
	const std::string ini = est.toIni();
	EXPECT_NE(ini.find("odo_noise_model = inflated"), std::string::npos) << ini;
	EXPECT_NE(ini.find("odo_tau_phi = "), std::string::npos) << ini;
}
