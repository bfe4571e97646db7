/** Markov-switching object motion ([ObjectMotion] model = markov, issue 28 item 4;
 * doc/simulator.md "Markov-switching object motion"): the modes are those of
 * estimator::CMultipleModel (same steps, same process noise, same switching matrix), the
 * empirical switch rate is the configured probability, the noise has the modes' covariance,
 * the ground truth follows the tracks, draws are seeded, bad keys are rejected naming them. */
#include <dynslam/core/models/mode_mixture.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/multiple_model.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <dynslam/sim/markov_motion.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam;

namespace
{
std::string markovIni()
{
	return dynslam_test::readFile(std::string(DYNSLAM_CONFIG_DIR) + "/tunnel_markov.ini");
}

sim::TScenarioOptions markov(const std::string& key = "", const std::string& value = "")
{
	std::string ini = markovIni();
	if (!key.empty()) ini = dynslam_test::setIniKey(ini, "ObjectMotion", key, value);
	return sim::loadScenarioFromText(ini);
}

/** s0 = [0; v0] of a car driving along x at `speed`. */
Eigen::VectorXd carStart(double speed)
{
	Eigen::VectorXd s = Eigen::VectorXd::Zero(6);
	s[3] = speed;
	return s;
}

/** The error message of loading the tunnel_markov INI with [ObjectMotion] key = value (and an
 * optional edit of the whole text), or "" if it loads. */
std::string loadError(const std::string& ini)
{
	try
	{
		sim::loadScenarioFromText(ini);
	}
	catch (const std::invalid_argument& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(SimMarkovMotion, ModesAreThoseOfTheMultipleModelFilter)
{
	const sim::TScenarioOptions o = markov();
	ASSERT_TRUE(o.object_motion.markov);
	estimator::TCvParams p;
	p.dt = o.dt;
	p.accel_psd = o.object_motion.accel_psd;
	p.mm_switch_prob = o.object_motion.switch_prob;
	p.mm_manoeuvre_psd = o.object_motion.manoeuvre_psd;
	const estimator::CMultipleModel mm(p);
	ASSERT_EQ(mm.modeCount(), sim::kMarkovModeCount);
	Eigen::VectorXd s(6);
	s << 3.0, -1.0, 0.2, 15.0, 0.7, 0.3;  // a turning car: the modes differ
	for (int j = 0; j < sim::kMarkovModeCount; ++j)
	{
		EXPECT_EQ(sim::markovModeName(j), mm.modeName(j));
		Eigen::MatrixXd Q;
		const Eigen::VectorXd f = mm.predictMode(j, s, nullptr, &Q);
		EXPECT_LT((sim::markovModeStep(j, s, o.dt) - f).norm(), 1e-12) << j;
		EXPECT_LT((sim::markovModeNoise(j, o.object_motion, 3, o.dt) - Q).norm(), 1e-15) << j;
	}
	// The turn mode is not the cv mode here (omega = 0.3 rad/s), the stationary one stops.
	EXPECT_GT((sim::markovModeStep(2, s, o.dt) - sim::markovModeStep(1, s, o.dt)).norm(), 0.1);
	EXPECT_EQ(sim::markovModeStep(0, s, o.dt).tail<3>(), Eigen::Vector3d::Zero());
	EXPECT_LT(
	    (models::uniformSwitching(4, o.object_motion.switch_prob) - mm.modeTransition()).norm(),
	    1e-15);
}

TEST(SimMarkovMotion, SwitchRateIsTheConfiguredProbability)
{
	// 2 cars x 4000 steps x 3 seeds = 24000 transitions per probability: the number of switches
	// is binomial(n, p); each other mode is the target with probability 1/3.
	for (const double p : {0.01, 0.05, 0.3})
	{
		sim::TScenarioOptions o = markov("switch_prob", std::to_string(p));
		o.steps = 4000;
		size_t n = 0, switches = 0;
		std::vector<int> to(4 * 4, 0);
		for (const uint32_t seed : {1u, 2u, 3u})
		{
			o.noise_seed = seed;
			for (const sim::TMarkovTrack& t :
			     sim::markovObjectTracks(o, {carStart(16), carStart(17)}))
				for (size_t k = 1; k < t.mode.size(); ++k, ++n)
					if (t.mode[k] != t.mode[k - 1])
					{
						++switches;
						++to[size_t(4 * t.mode[k - 1] + t.mode[k])];
					}
		}
		const double mean = double(n) * p, sd = std::sqrt(double(n) * p * (1 - p));
		EXPECT_NEAR(double(switches), mean, 4 * sd) << "p = " << p;
		// From each mode, the three targets: chi-square with 2 dof per mode (8 in all).
		double chi2 = 0;
		for (int i = 0; i < 4; ++i)
		{
			double out = 0;
			for (int j = 0; j < 4; ++j) out += to[size_t(4 * i + j)];
			for (int j = 0; j < 4; ++j)
				if (j != i && out > 0)
					chi2 += std::pow(to[size_t(4 * i + j)] - out / 3, 2) / (out / 3);
		}
		EXPECT_LT(chi2, 26.12) << "p = " << p;  // chi2(8) 99.9 % quantile
	}
	// p = 0: never a switch; the cars keep initial_mode.
	sim::TScenarioOptions o = markov("switch_prob", "0");
	o.steps = 2000;
	for (const sim::TMarkovTrack& t : sim::markovObjectTracks(o, {carStart(16)}))
		for (int m : t.mode) EXPECT_EQ(m, 1);
}

TEST(SimMarkovMotion, NoiseHasTheModesCovariance)
{
	// The residual w_k = s_k - f_mode(s_{k-1}) normalised by the mode's Q: chi2(6) per step.
	sim::TScenarioOptions o = markov("switch_prob", "0.1");
	o.object_motion.accel_psd << 1e-3, 1e-4, 1e-5;  // every axis noisy: Q positive definite
	o.steps = 1500;
	o.noise_seed = 11;
	double sum = 0;
	size_t n = 0;
	Eigen::Vector4i used = Eigen::Vector4i::Zero();
	for (const sim::TMarkovTrack& t : sim::markovObjectTracks(o, {carStart(16), carStart(12)}))
		for (size_t k = 1; k < t.mode.size(); ++k, ++n)
		{
			const int m = t.mode[k];
			++used[m];
			Eigen::VectorXd w = t.state[k] - sim::markovModeStep(m, t.state[k - 1], o.dt);
			w[2] = models::wrapToPi(w[2]);
			const Eigen::MatrixXd Q = sim::markovModeNoise(m, o.object_motion, 3, o.dt);
			sum += w.dot(Q.ldlt().solve(w));
		}
	EXPECT_GT(used.minCoeff(), 100);  // every mode was visited
	const auto [lo, hi] = dynslam_test::chi2Interval(6.0 * double(n));
	EXPECT_GT(sum, lo);
	EXPECT_LT(sum, hi);
}

TEST(SimMarkovMotion, GroundTruthFollowsTheTracksAndIsSeeded)
{
	sim::TScenarioOptions o = markov();
	o.steps = 120;
	o.start_from_prior = false;  // else the whole world (object poses too) is turned by x0
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	// config/tunnel_markov.ini: Agent1 at 16.8 m/s, Agent2 at 17 m/s, both seen at step 0.
	const auto tracks = sim::markovObjectTracks(o, {carStart(16.8), carStart(17.0)});
	ASSERT_EQ(gt.objects.size(), 2u);
	for (size_t i = 0; i < 2; ++i)
	{
		ASSERT_EQ(gt.objects[i].first_step, 0);
		for (size_t k = 0; k < gt.ego.size(); ++k)
		{
			const Eigen::Vector3d xi = tracks[i].state[k].head<3>();
			Eigen::Vector3d e = gt.objects[i].pose[k] - xi;
			e[2] = models::wrapToPi(e[2]);
			EXPECT_LT(e.norm(), 1e-5) << i << " " << k;  // v0 by a 1e-6 s forward difference
		}
	}
	// Modes do switch in this run, and the cars leave the scripted motion.
	int switches = 0;
	for (const auto& t : tracks)
		for (size_t k = 1; k < t.mode.size(); ++k) switches += t.mode[k] != t.mode[k - 1];
	EXPECT_GT(switches, 0);
	// Seeded: the same noise seed gives the same truth, another one another truth; the
	// deterministic truth (the section absent) differs.
	const io::TGroundTruth again = sim::buildGroundTruth(o);
	EXPECT_EQ(again.objects[0].features, gt.objects[0].features);
	sim::TScenarioOptions other = o;
	other.noise_seed = o.noise_seed + 1;
	EXPECT_NE(sim::buildGroundTruth(other).objects[0].features.back(),
	          gt.objects[0].features.back());
	// The effective configuration reads back to the same options and truth.
	std::ostringstream dumped;
	o.dumpToTextStream(dumped);
	const sim::TScenarioOptions back = sim::loadScenarioFromText(dumped.str());
	EXPECT_TRUE(back.object_motion.markov);
	EXPECT_EQ(back.object_motion.switch_prob, o.object_motion.switch_prob);
	EXPECT_EQ(back.object_motion.manoeuvre_psd, o.object_motion.manoeuvre_psd);
	EXPECT_EQ(sim::buildGroundTruth(back).objects[1].features, gt.objects[1].features);
}

TEST(SimMarkovMotion, BadKeysAreRejectedNamingThem)
{
	const std::string ini = markovIni();
	auto with = [&](const std::string& key, const std::string& value)
	{ return loadError(dynslam_test::setIniKey(ini, "ObjectMotion", key, value)); };
	const std::vector<std::tuple<std::string, std::string, std::string>> bad{
	    {"model", "random", "[ObjectMotion] model"},
	    {"switch_prob", "1", "[ObjectMotion] switch_prob = '1': must be in [0, 1)"},
	    {"switch_prob", "-0.01", "[ObjectMotion] switch_prob"},
	    {"switch_prob", "abc", "[ObjectMotion] switch_prob"},
	    {"accel_psd", "[1e-7 -1e-7 1e-9]", "[ObjectMotion] accel_psd"},
	    {"accel_psd", "[1e-7 1e-7]", "[ObjectMotion] accel_psd"},
	    {"manoeuvre_psd", "[1 1 nan]", "[ObjectMotion] manoeuvre_psd"},
	    {"initial_mode", "flying", "[ObjectMotion] initial_mode"},
	    {"switch_rate", "0.1", "[ObjectMotion] switch_rate"}};
	for (const auto& [key, value, msg] : bad)
		EXPECT_NE(with(key, value).find(msg), std::string::npos)
		    << key << " = " << value << ": " << with(key, value);
	// Both sides of the switch_prob boundaries load.
	for (const char* ok : {"0", "0.999"}) EXPECT_EQ(with("switch_prob", ok), "") << ok;
	// A missing required key, the keys without model = markov, two object truths at once.
	const std::string noSwitch = dynslam_test::removeIniKey(ini, "ObjectMotion", "switch_prob");
	EXPECT_NE(loadError(noSwitch).find("[ObjectMotion] switch_prob"), std::string::npos)
	    << loadError(noSwitch);
	EXPECT_NE(with("model", "deterministic").find("only with model = markov"), std::string::npos);
	const std::string both =
	    dynslam_test::setIniKey(ini, "Noise", "object_accel_psd", "[1e-3 1e-5 1e-7]");
	EXPECT_NE(loadError(both).find("conflicts with [Noise] object_accel_psd"), std::string::npos)
	    << loadError(both);
}
