/** The compressed EKF (static_update = compressed, estimator/compressed_state.h) equals the
 * full EKF (the sparse update) to rounding after a global update: on the highway rawlog, a
 * generated scenario and a ring with revisits, with each drop policy and with first-estimate
 * Jacobians, at random checkpoints (each a global update, after which the filter compresses
 * again) and at the end of runs never expanded before. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/compressed_state.h>
#include <gtest/gtest.h>

#include <random>

#include "compressed_runs.h"

using namespace dynslam;

namespace
{
using namespace compressed_runs;

struct TPolicy
{
	const char* name;
	int drop_static = 0, keep_poses = 1;
	bool drop_time_t = true, smoothing = false, fej = false;
};

void configure(CDynamicKFSLAM2D& f, const TSteps& s, const TPolicy& p, bool compressed)
{
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = s.Sigma_v;
	f.options.Sigma_0 = s.Sigma_0;
	f.options.drop_static_after_unseen_steps = p.drop_static;
	f.options.keep_last_poses = p.keep_poses;
	f.options.drop_time_t_features = p.drop_time_t;
	f.options.smoothing = p.smoothing;
	f.options.first_estimate_jacobians = p.fej;
	f.options.compressed_static_update = compressed;
	f.reset();
}

void runAndCompare(const TSteps& s, const TPolicy& p, const std::string& data)
{
	CDynamicKFSLAM2D full, atCheckpoints, neverExpanded, eager;
	configure(full, s, p, false);
	configure(atCheckpoints, s, p, true);
	configure(neverExpanded, s, p, true);
	eager.setStateLifecycle(std::make_unique<estimator::CCompressedLifecycle>(1, 1));
	configure(eager, s, p, true);
	ASSERT_EQ(atCheckpoints.stateLifecycle().name(), "compressed");
	ASSERT_EQ(eager.stateLifecycle().name(), "compressed");
	std::mt19937 rng(11);
	std::uniform_int_distribution<size_t> pick(0, s.acts.size() - 1);
	std::set<size_t> checkpoints;
	for (int i = 0; i < 6; ++i) checkpoints.insert(pick(rng));
	size_t maxPassive = 0;
	double worst = 0;
	for (size_t k = 0; k < s.acts.size(); ++k)
	{
		for (auto* f : {&full, &atCheckpoints, &neverExpanded, &eager})
			f->processActionObservation(s.acts[k], s.sfs[k]);
		maxPassive = std::max({maxPassive, neverExpanded.passiveLandmarks(),
		                       atCheckpoints.passiveLandmarks(), eager.passiveLandmarks()});
		if (checkpoints.count(k))
		{
			atCheckpoints.globalUpdate();  // the working state expanded, compressed again later
			EXPECT_EQ(atCheckpoints.workingDim(), atCheckpoints.fullMean().size());
			EXPECT_EQ(atCheckpoints.passiveLandmarks(), 0u);
			const auto e =
			    compare(full, atCheckpoints, data + "/" + p.name + " step " + std::to_string(k));
			worst = std::max({worst, e.first, e.second});
		}
	}
	// Not vacuous: landmarks were passive at some point (with drop_static_4 they are dropped 1-3
	// steps after they become passive: a global update before each such drop).
	EXPECT_GT(maxPassive, p.drop_static > 0 ? 0u : 5u) << data << "/" << p.name;
	for (auto* c : {&neverExpanded, &eager, &atCheckpoints})
	{
		const auto e = compare(full, *c, data + "/" + p.name + " end");
		worst = std::max({worst, e.first, e.second});
	}
	std::cout << data << "/" << p.name << ": worst relative error " << worst
	          << ", most passive landmarks " << maxPassive << "\n";
}

const TPolicy kPolicies[] = {
    {"default"},
    {"drop_static_4", 4},
    {"keep_3_poses_time_t_kept_smoothing", 0, 3, false, true},
    {"fej", 0, 1, true, false, true},
};

class CompressedEqualsFull : public ::testing::TestWithParam<int>
{
};
}  // namespace

TEST_P(CompressedEqualsFull, Highway)
{
	static const TSteps s = highway();
	runAndCompare(s, kPolicies[GetParam()], "highway");
}

TEST_P(CompressedEqualsFull, GeneratedScenario)
{
	static const TSteps s = generated();
	runAndCompare(s, kPolicies[GetParam()], "generated_small");
}

TEST_P(CompressedEqualsFull, RingWithRevisits)
{
	static const TSteps s = ring();
	runAndCompare(s, kPolicies[GetParam()], "ring");
}

INSTANTIATE_TEST_SUITE_P(DropPolicies, CompressedEqualsFull, ::testing::Range(0, 4));

TEST(CompressedState, CompressThenExpandIsTheIdentity)
{
	// A random covariance over ego + 6 landmarks + a 3-dof pose (a pad); landmarks 1, 2, 4
	// passive, then expanded: the same Gaussian, landmarks reordered.
	estimator::CPaddedLayout L;
	for (int i = 0; i < 6; ++i) L.append({estimator::BlockKind::StaticLandmark, 100 + i});
	estimator::TBlock pose;
	pose.kind = estimator::BlockKind::ObjectPose;
	pose.object = 0;
	pose.dim = 3;
	L.append(pose);
	const int n = L.storageDim();
	std::mt19937 rng(5);
	std::normal_distribution<double> g;
	Eigen::MatrixXd A(n, n);
	for (int i = 0; i < n * n; ++i) A.data()[i] = g(rng);
	ekf::RowMatrixXd P = A * A.transpose();
	Eigen::VectorXd x(n);
	for (int i = 0; i < n; ++i) x[i] = g(rng);
	std::vector<bool> passive{false, true, true, false, true, false, false};
	std::vector<estimator::TPassiveLevel> levels;
	Eigen::VectorXd xc;
	ekf::RowMatrixXd Pc;
	estimator::CPaddedLayout Lc = L;
	levels.push_back(estimator::compressState(x, P, Lc, passive, 0, xc, Pc));
	EXPECT_EQ(xc.size(), 13 + 14);  // kept: ego, 3 landmarks, the pose; C: 13 + 1
	estimator::expandState(xc, Pc, Lc, levels);
	ASSERT_EQ(Lc.size(), L.size());
	std::vector<int> perm{0, 1, 2};
	for (size_t b = 0; b < Lc.size(); ++b)
		for (size_t a = 0; a < L.size(); ++a)
			if (L[a].kind == Lc[b].kind && L[a].id == Lc[b].id)
				for (int i = 0; i < 2 * L[a].slots(); ++i) perm.push_back(L.first(a) + i);
	ASSERT_EQ(int(perm.size()), n);
	EXPECT_LE((xc - x(perm)).cwiseAbs().maxCoeff(), 1e-14);
	EXPECT_LE((Pc - P(perm, perm)).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_TRUE(levels.empty());
}
