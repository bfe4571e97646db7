/** Landmark fusion (fuse_landmarks_prob, issue 29 item 1; estimator/landmark_fusion.h): the
 * conditioning of the state helper against a dense Kalman update on the difference, the test
 * on both sides of its chi-square threshold, the ambiguity rule and the alias table, and the
 * key's bad input. */
#include <dynslam/common/model_options.h>
#include <dynslam/core/chi2.h>
#include <dynslam/estimator/landmark_fusion.h>
#include <dynslam/estimator/state_helper.h>
#include <dynslam_test/option_errors.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Dense>
#include <map>
#include <random>

#include "any_backend.h"

using namespace dynslam;
using estimator::CLandmarkFusion;

namespace
{
/** A random SPD matrix with strong correlations. */
ekf::RowMatrixXd randomCov(int n, unsigned seed)
{
	std::mt19937 g(seed);
	std::normal_distribution<double> N(0, 1);
	Eigen::MatrixXd L(n, n);
	for (int r = 0; r < n; ++r)
		for (int c = 0; c < n; ++c) L(r, c) = N(g);
	return L * L.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
}

/** The dense reference: the Kalman update with H = [.. I_a .. -I_b ..], reading 0, R = 0, in
 * Joseph form on the full covariance, then b's rows and columns deleted. */
void denseFusion(Eigen::VectorXd& x, Eigen::MatrixXd& P, const std::vector<int>& a,
                 const std::vector<int>& b)
{
	const Eigen::Index n = x.size();
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
	for (int k = 0; k < 2; ++k) H(k, a[k]) = 1, H(k, b[k]) = -1;
	const Eigen::MatrixXd S = H * P * H.transpose();
	const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
	x = x + K * (Eigen::Vector2d::Zero() - H * x);
	const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(n, n) - K * H;
	P = IKH * P * IKH.transpose();
	std::vector<int> keep;
	for (int i = 0; i < n; ++i)
		if (i != b[0] && i != b[1]) keep.push_back(i);
	x = Eigen::VectorXd(x(keep));
	P = Eigen::MatrixXd(P(keep, keep));
}

std::vector<int> without(int n, const std::vector<int>& b)
{
	std::vector<int> keep;
	for (int i = 0; i < n; ++i)
		if (std::find(b.begin(), b.end(), i) == b.end()) keep.push_back(i);
	return keep;
}
}  // namespace

TEST(LandmarkFusion, ConditionThenRemovalEqualsTheDenseUpdate)
{
	for (unsigned seed = 1; seed <= 5; ++seed)
	{
		const int n = 13;  // ego + 5 landmarks
		const ekf::RowMatrixXd P0 = randomCov(n, seed);
		std::mt19937 g(seed + 100);
		std::normal_distribution<double> N(0, 1);
		Eigen::VectorXd x0(n);
		for (int i = 0; i < n; ++i) x0[i] = N(g);
		const std::vector<int> a{5, 6}, b{9, 10};
		Eigen::VectorXd x = x0;
		ekf::RowMatrixXd P = P0;
		estimator::state::condition(x, P, a, b);
		EXPECT_LT((x(a) - x(b)).norm(), 1e-12);
		EXPECT_EQ(P, P.transpose());
		EXPECT_LT((P(a, Eigen::all) - P(b, Eigen::all)).cwiseAbs().maxCoeff(), 1e-12);
		const std::vector<int> keep = without(n, b);
		Eigen::VectorXd xd = x0;
		Eigen::MatrixXd Pd = P0;
		denseFusion(xd, Pd, a, b);
		EXPECT_LT((Eigen::VectorXd(x(keep)) - xd).cwiseAbs().maxCoeff(), 1e-9) << seed;
		EXPECT_LT((Eigen::MatrixXd(P(keep, keep)) - Pd).cwiseAbs().maxCoeff(), 1e-9) << seed;
	}
}

TEST(LandmarkFusion, ConditionBadInput)
{
	Eigen::VectorXd x = Eigen::VectorXd::Zero(7);
	ekf::RowMatrixXd P = ekf::RowMatrixXd::Identity(7, 7);
	EXPECT_THROW(estimator::state::condition(x, P, {3, 4}, {5}), std::invalid_argument);
	EXPECT_THROW(estimator::state::condition(x, P, {3, 4}, {4, 5}), std::invalid_argument);
	EXPECT_THROW(estimator::state::condition(x, P, {3, 4}, {5, 7}), std::invalid_argument);
	// Two entries that are already one (their difference has no variance): not conditioned.
	P(3, 5) = P(5, 3) = P(4, 6) = P(6, 4) = 1;
	EXPECT_THROW(estimator::state::condition(x, P, {3, 4}, {5, 6}), std::runtime_error);
	EXPECT_EQ(P(3, 3), 1);
}

TEST(LandmarkFusion, TestOnBothSidesOfItsThreshold)
{
	// Two landmarks with a strong cross-covariance (a landmark initialised from an ego whose
	// uncertainty it shares with an old one): S must include P_ij and P_ji.
	// Landmark b = landmark a + a small independent error: P_ab = P_aa, S = the small error's
	// covariance, while P_aa + P_bb alone is more than twice P_aa.
	const int n = 7;
	Eigen::MatrixXd J = Eigen::MatrixXd::Identity(n, n);
	J.block(5, 3, 2, 2) = Eigen::Matrix2d::Identity();
	J.block(5, 5, 2, 2) = 0.2 * Eigen::Matrix2d::Identity();
	const ekf::RowMatrixXd P = J * randomCov(n, 11) * J.transpose();
	const std::vector<int> a{3, 4}, b{5, 6};
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
	for (int k = 0; k < 2; ++k) H(k, a[k]) = 1, H(k, b[k]) = -1;
	const Eigen::Matrix2d S = H * P * H.transpose();
	const Eigen::Matrix2d Snaive = P(a, a) + P(b, b);
	ASSERT_GT((S - Snaive).norm(), 0.3 * S.norm()) << "the cross terms must matter here";
	const double p = 0.99, thr = chi2Quantile(p, 2);
	EXPECT_NEAR(estimator::fusionThreshold(p), -2 * std::log(1 - p), 1e-9);
	const Eigen::Vector2d dir(0.6, -0.8);
	const double unit = dir.dot(S.inverse() * dir);
	for (const double f : {1 - 1e-6, 1 + 1e-6})
	{
		Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
		const Eigen::Vector2d d = std::sqrt(f * thr / unit) * dir;
		x(a) = Eigen::Vector2d(10, 20) + d;
		x(b) = Eigen::Vector2d(10, 20);
		const double d2 = estimator::fusionDistance2(x, P, a, b);
		EXPECT_NEAR(d2, f * thr, 1e-9 * thr);
		// Landmark 1 read in steps 0..4, landmark 2 (a new ID) from step 6 on.
		CLandmarkFusion fusion(p);
		fusion.noteRead(1, 0, x(a));
		fusion.noteRead(1, 4, x(a));
		fusion.noteRead(2, 6, x(b));
		const std::map<int32_t, std::vector<int>> idx{{1, a}, {2, b}};
		const auto pairs =
		    fusion.decide({2}, [&](int32_t i, int32_t j)
		                  { return estimator::fusionDistance2(x, P, idx.at(i), idx.at(j)); });
		if (f < 1)
		{
			ASSERT_EQ(pairs.size(), 1u) << "d2 = " << d2 << " just inside " << thr;
			EXPECT_EQ(pairs[0].keep, 1);  // the older one stays
			EXPECT_EQ(pairs[0].gone, 2);
		}
		else
			EXPECT_TRUE(pairs.empty()) << "d2 = " << d2 << " just outside " << thr;
	}
}

namespace
{
/** A fusion bookkeeping with landmarks at given points and reading intervals, and a table of
 * test statistics (missing pairs: far outside the threshold). */
struct TToy
{
	CLandmarkFusion f{0.99};
	std::map<std::pair<int32_t, int32_t>, double> d2;
	size_t calls = 0;
	void add(int32_t id, int first, int last, Eigen::Vector2d p)
	{
		f.noteRead(id, first, p);
		f.noteRead(id, last, p);
	}
	void pass(int32_t a, int32_t b) { d2[{a, b}] = d2[{b, a}] = 1.0; }
	std::vector<estimator::TFusionPair> decide(const std::vector<int32_t>& read)
	{
		return f.decide(read,
		                [&](int32_t a, int32_t b)
		                {
			                ++calls;
			                const auto it = d2.find({a, b});
			                return it == d2.end() ? 1e6 : it->second;
		                });
	}
};
}  // namespace

TEST(LandmarkFusion, AmbiguityRule)
{
	const Eigen::Vector2d p(1, 1);
	{  // one compatible each way: fused, the older kept
		TToy t;
		t.add(7, 0, 5, p);
		t.add(9, 8, 8, p);
		t.pass(7, 9);
		const auto pairs = t.decide({9});
		ASSERT_EQ(pairs.size(), 1u);
		EXPECT_EQ(pairs[0].keep, 7);
		EXPECT_EQ(pairs[0].gone, 9);
	}
	{  // the new one has two compatible landmarks: none fused
		TToy t;
		t.add(7, 0, 5, p);
		t.add(8, 0, 6, p + Eigen::Vector2d(0.01, 0));
		t.add(9, 8, 8, p);
		t.pass(7, 9);
		t.pass(8, 9);
		EXPECT_TRUE(t.decide({9}).empty());
	}
	{  // its single candidate has another compatible one (10, read later): none fused
		TToy t;
		t.add(7, 0, 5, p);
		t.add(9, 8, 8, p);
		t.add(10, 9, 12, p + Eigen::Vector2d(0.01, 0));
		t.pass(7, 9);
		t.pass(7, 10);
		EXPECT_TRUE(t.decide({9}).empty());
		EXPECT_TRUE(t.decide({10}).empty());
	}
	{  // read in a common step: two points, never compared (even with d2 = 0)
		TToy t;
		t.add(7, 0, 8, p);
		t.add(9, 8, 8, p);
		t.d2[{7, 9}] = t.d2[{9, 7}] = 0;
		EXPECT_TRUE(t.decide({9}).empty());
		EXPECT_EQ(t.calls, 0u);
	}
	{  // beyond the 3 x 3 cells of the grid: not a neighbour (never tested)
		TToy t;
		t.add(7, 0, 5, p);
		t.add(9, 8, 8, p + Eigen::Vector2d(2.5 * CLandmarkFusion::kCell, 0));
		t.pass(7, 9);
		EXPECT_TRUE(t.decide({9}).empty());
		EXPECT_EQ(t.calls, 0u);
	}
}

TEST(LandmarkFusion, AliasesFollowTheLandmarkAndAreForgottenWithIt)
{
	CLandmarkFusion f(0.99);
	const Eigen::Vector2d p(0, 0);
	for (const int32_t id : {1, 2, 3}) f.noteRead(id, int(id) * 10, p);
	f.fused(2, 3, p);  // 3 read as 2
	EXPECT_EQ(f.resolve(3), 2);
	f.fused(1, 2, p);  // 2 and 3 read as 1
	EXPECT_EQ(f.resolve(2), 1);
	EXPECT_EQ(f.resolve(3), 1);
	EXPECT_EQ(f.aliased(), 2u);
	EXPECT_EQ(f.registered(), 1u);
	f.forget(1);  // landmark 1 left the state: its IDs start anew
	EXPECT_EQ(f.resolve(2), 2);
	EXPECT_EQ(f.resolve(3), 3);
	EXPECT_EQ(f.aliased(), 0u);
	EXPECT_EQ(f.registered(), 0u);
	EXPECT_THROW(f.fused(1, 2, p), std::logic_error);
}

TEST(LandmarkFusion, BadInputIsAClearError)
{
	const std::string head = "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1 1]\n";
	{
		mrpt::config::CConfigFileMemory c(head + "fuse_landmarks_prob = 0\n");
		TModelOptions o;
		ASSERT_NO_THROW(o.loadFromConfigFile(c, "DynamicKFSLAM"));
		EXPECT_EQ(o.fuse_landmarks_prob, 0);
		EXPECT_FALSE(CLandmarkFusion(o.fuse_landmarks_prob).enabled());
		TModelOptions d;
		EXPECT_EQ(d.fuse_landmarks_prob, 0) << "off by default";
	}
	for (const auto& [keys, word] : std::vector<std::pair<std::string, std::string>>{
	         {"fuse_landmarks_prob = 1\n", "(0, 1)"},
	         {"fuse_landmarks_prob = -0.1\n", "(0, 1)"},
	         {"fuse_landmarks_prob = 1.5\n", "(0, 1)"},
	         {"fuse_landmarks_prob = nan\n", "not a number"},
	         {"fuse_landmarks_prob = 0.99\nfeature_labels = classify\n", "feature_labels = ids"},
	         {"fuse_landmarks_prob = 0.99\nstatic_update = compressed\n", "compressed"}})
		dynslam_test::expectOptionsError(head + keys, {"fuse_landmarks_prob", word});
	for (const double p : {1.0, -0.1, 1.5})
		EXPECT_THROW(CLandmarkFusion{p}, std::invalid_argument) << p;
	// The framework's back-ends do not implement it.
	const std::string ini =
	    head + "Sigma_0 = [1e-6 1e-6 1e-8]\nfuse_landmarks_prob = 0.99\n[Framework]\n";
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		if (kind == "ekf") continue;
		try
		{
			dynslam_test::anyBackend(kind, ini);
			ADD_FAILURE() << kind;
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("fuse_landmarks_prob"), std::string::npos)
			    << kind << ": " << e.what();
		}
	}
}
