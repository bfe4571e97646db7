/** The model-matched truth ([Noise] start_from_prior, object_accel_psd; doc/simulator.md
 * "Model-matched truth", issue 13): the true start drawn from N(0, Sigma_0) moves the whole
 * world rigidly (the readings do not change), the objects' poses get offsets that follow the CV
 * model of models/object_motion.h; both with the statistics they claim, keys dumped only when
 * set, bad values rejected naming the key. */
#include <dynslam/core/models/object_motion.h>
#include <dynslam/core/models/se2.h>
#include <dynslam/sim/TScenarioOptions.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <sstream>

#include "sim_test_utils.h"

using namespace dynslam;

namespace
{
std::string tunnelWith(const std::string& keys)
{
	std::string ini = dynslam_test::readFile(std::string(DYNSLAM_CONFIG_DIR) + "/tunnel.ini");
	const size_t at = ini.find("[Noise]\n");
	EXPECT_NE(at, std::string::npos);
	return ini.insert(at + 8, keys);
}

sim::TScenarioOptions tunnel(const std::string& keys, int steps, uint32_t seed)
{
	sim::TScenarioOptions o = sim::loadScenarioFromText(tunnelWith(keys));
	o.steps = steps;
	o.noise_seed = seed;
	return o;
}
}  // namespace

TEST(SimModelMatchedTruth, StartFromThePriorMovesTheWorldRigidly)
{
	const sim::TScenarioOptions clean = tunnel("", 40, 7);
	const sim::TScenarioOptions drawn = tunnel("start_from_prior = true\n", 40, 7);
	const io::TGroundTruth gc = sim::buildGroundTruth(clean), gd = sim::buildGroundTruth(drawn);
	const Eigen::Vector3d x0 = gd.ego[0];
	EXPECT_EQ(gc.ego[0], Eigen::Vector3d::Zero());
	EXPECT_GT(x0.head<2>().norm(), 1e-5);  // a draw of std 3.2e-3 m per axis
	for (size_t k = 0; k < gc.ego.size(); ++k)
		EXPECT_LT((gd.ego[k] - models::composePose(x0, gc.ego[k])).norm(), 1e-9) << k;
	for (const auto& [id, p] : gc.landmarks)
		EXPECT_LT((gd.landmarks.at(id) - models::rot2(x0[2]) * p - x0.head<2>()).norm(), 1e-9);
	for (size_t i = 0; i < gc.objects.size(); ++i)
		for (size_t k = 0; k < gc.ego.size(); ++k)
		{
			const Eigen::Matrix2Xd moved =
			    (models::rot2(x0[2]) * gc.objects[i].features[k]).colwise() + x0.head<2>();
			EXPECT_LT((gd.objects[i].features[k] - moved).norm(), 1e-9);
		}
	// The readings are relative: the same (up to float storage) with the same noise seed.
	const auto rc = sim::simulateMeasurements(gc, clean, 7);
	const auto rd = sim::simulateMeasurements(gd, drawn, 7);
	size_t readings = 0;
	for (size_t k = 0; k < rc.frames.size(); ++k)
	{
		const auto a = rc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		const auto b = rd.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		ASSERT_EQ(a->sensedData.size(), b->sensedData.size());
		for (size_t j = 0; j < a->sensedData.size(); ++j, ++readings)
		{
			EXPECT_EQ(a->sensedData[j].landmarkID, b->sensedData[j].landmarkID);
			EXPECT_NEAR(a->sensedData[j].range, b->sensedData[j].range, 1e-5);
			EXPECT_NEAR(a->sensedData[j].yaw, b->sensedData[j].yaw, 1e-6);
		}
	}
	EXPECT_GT(readings, 100u);
}

TEST(SimModelMatchedTruth, StartDrawsHaveThePriorCovariance)
{
	// 2000 draws: sum of x0^T Sigma_0^-1 x0 is chi-square with 6000 dof if x0 ~ N(0, Sigma_0).
	const int n = 2000;
	double sum = 0;
	Eigen::Vector3d mean = Eigen::Vector3d::Zero();
	for (int s = 0; s < n; ++s)
	{
		const sim::TScenarioOptions o = tunnel("start_from_prior = true\n", 1, 100 + s);
		const Eigen::Vector3d x0 = sim::buildGroundTruth(o).ego[0];
		sum += x0.dot(o.Sigma_0.ldlt().solve(x0));
		mean += o.Sigma_0.diagonal().cwiseSqrt().cwiseInverse().cwiseProduct(x0) / n;
	}
	const auto [lo, hi] = dynslam_test::chi2Interval(3.0 * n);
	std::printf("[ measured ] %d start draws: sum of squared Mahalanobis %.1f in [%.1f, %.1f]\n", n,
	            sum, lo, hi);
	EXPECT_GT(sum, lo);
	EXPECT_LT(sum, hi);
	EXPECT_LT(mean.cwiseAbs().maxCoeff(), 3.29 / std::sqrt(double(n)));  // each N(0, 1 / n)
}

TEST(SimModelMatchedTruth, ObjectOffsetsFollowTheCvModel)
{
	// The offset of each object's pose (centroid translation, rotation about the centroid) at
	// the last step K, over 400 seeds and the tunnel's 2 cars, against the CV model's covariance
	// (P_K = F P F^T + Q, K times from 0): sum of squared normalized offsets, 3 x 800 dof.
	const Eigen::Vector3d q(1e-3, 1e-3, 1e-5);
	const int K = 20, n = 400;
	const std::string keys = "object_accel_psd = [1e-3 1e-3 1e-5]\n";
	Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6, 6), F;
	const double dt = tunnel("", K, 1).dt;
	models::cvPredict(Eigen::VectorXd::Zero(6), dt, &F);
	for (int k = 0; k < K; ++k) P = F * P * F.transpose() + models::cvProcessNoise(q, dt);
	double sum = 0;
	int samples = 0;
	const io::TGroundTruth gc = sim::buildGroundTruth(tunnel("", K, 1));
	for (int s = 0; s < n; ++s)
	{
		const io::TGroundTruth g = sim::buildGroundTruth(tunnel(keys, K, 500 + s));
		EXPECT_EQ(g.ego, gc.ego);  // the ego is untouched
		for (size_t i = 0; i < g.objects.size(); ++i, ++samples)
		{
			const Eigen::Matrix2Xd& a = gc.objects[i].features[K];
			const Eigen::Matrix2Xd& b = g.objects[i].features[K];
			const Eigen::Vector2d ca = a.rowwise().mean(), cb = b.rowwise().mean();
			const Eigen::Vector2d ra = a.col(0) - ca, rb = b.col(0) - cb;
			const double th = std::atan2(ra.x() * rb.y() - ra.y() * rb.x(), ra.dot(rb));
			// rigid: every feature is the rotation about the centroid plus the shift
			EXPECT_LT((b - ((models::rot2(th) * (a.colwise() - ca)).colwise() + cb)).norm(), 1e-9);
			const Eigen::Vector3d d(cb.x() - ca.x(), cb.y() - ca.y(), th);
			for (int j = 0; j < 3; ++j) sum += d[j] * d[j] / P(j, j);
		}
	}
	const auto [lo, hi] = dynslam_test::chi2Interval(3.0 * samples);
	std::printf("[ measured ] %d object offsets at step %d: sum %.1f in [%.1f, %.1f]\n", samples, K,
	            sum, lo, hi);
	EXPECT_GT(sum, lo);
	EXPECT_LT(sum, hi);
}

TEST(SimModelMatchedTruth, KeysDumpedOnlyWhenSetReloadedAndChecked)
{
	std::ostringstream off;
	sim::loadScenarioFromText(tunnelWith("")).dumpToTextStream(off);
	EXPECT_EQ(off.str().find("start_from_prior"), std::string::npos);
	EXPECT_EQ(off.str().find("object_accel_psd"), std::string::npos);
	const sim::TScenarioOptions o = sim::loadScenarioFromText(
	    tunnelWith("start_from_prior = true\nobject_accel_psd = [1e-7 2e-7 1e-9]\n"));
	EXPECT_TRUE(o.start_from_prior);
	EXPECT_EQ(o.object_accel_psd, Eigen::Vector3d(1e-7, 2e-7, 1e-9));
	std::ostringstream a, b;
	o.dumpToTextStream(a);
	const sim::TScenarioOptions o2 = sim::loadScenarioFromText(a.str());
	o2.dumpToTextStream(b);
	EXPECT_EQ(a.str(), b.str());
	EXPECT_TRUE(o2.start_from_prior);
	EXPECT_EQ(o2.object_accel_psd, o.object_accel_psd);
	for (const std::string bad :
	     {"object_accel_psd = [1e-7 -1e-7 0]\n", "object_accel_psd = [nan 0 0]\n",
	      "object_accel_psd = [1 2]\n", "start_from_prior = maybe\n"})
	{
		try
		{
			sim::loadScenarioFromText(tunnelWith(bad));
			ADD_FAILURE() << "accepted " << bad;
		}
		catch (const std::invalid_argument& e)
		{
			const std::string key = bad.substr(0, bad.find(' '));
			EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
		}
	}
}
