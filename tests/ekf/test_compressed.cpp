/** The compressed EKF (static_update = compressed, estimator/compressed_state.h) equals the
 * full EKF (the sparse update) to rounding after a global update: on the highway rawlog, a
 * generated scenario and a ring with revisits, with each drop policy and with first-estimate
 * Jacobians, at random checkpoints (each a global update, after which the filter compresses
 * again) and at the end of runs never expanded before. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/compressed_state.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <map>
#include <random>

#include "synthetic_world.h"

using namespace dynslam;

namespace
{
struct TSteps
{
	std::vector<mrpt::obs::CActionCollection::Ptr> acts;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> sfs;
	Eigen::Matrix2d Sigma_v;
	Eigen::Matrix3d Sigma_0;
};

TSteps highway()
{
	mrpt::obs::CRawlog log;
	if (!log.loadFromRawLogFile(DYNSLAM_DATASETS_DIR "/highway.rawlog"))
		throw std::runtime_error("highway.rawlog");
	TSteps s;
	for (size_t i = 0; i + 1 < log.size(); ++i)
		if (log.getType(i) == mrpt::obs::CRawlog::etActionCollection &&
		    log.getType(i + 1) == mrpt::obs::CRawlog::etSensoryFrame)
		{
			s.acts.push_back(log.getAsAction(i));
			s.sfs.push_back(log.getAsObservations(i + 1));
			++i;
		}
	const auto o = sim::loadScenario(DYNSLAM_DATASETS_DIR "/highway_scenario.ini");
	s.Sigma_v = o.Sigma_v;
	s.Sigma_0 = o.Sigma_0;
	return s;
}

TSteps generated()
{
	const auto o = sim::loadScenario(DYNSLAM_CONFIG_DIR "/generated_small_scenario.ini");
	const auto run = sim::simulateMeasurements(sim::buildGroundTruth(o), o, 7);
	return {run.actions, run.frames, o.Sigma_v, o.Sigma_0};
}

/** A ring of 60 landmarks driven 2.5 times round (every landmark read again after a lap), 2
 * objects in convoy. */
TSteps ring()
{
	dynslam_bench::TSyntheticOptions o;
	o.landmarks = 60;
	o.spacing = 6;
	o.objects = 2;
	o.max_visible = 12;
	o.seed = 3;
	dynslam_bench::CSyntheticWorld w(o);
	TSteps s;
	s.Sigma_v = o.Sigma_v;
	s.Sigma_0 = o.Sigma_w;
	for (int k = 0; k < 480; ++k)
	{
		s.acts.emplace_back();
		s.sfs.emplace_back();
		w.next(s.acts.back(), s.sfs.back());
	}
	return s;
}

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

double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
	return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, a.cwiseAbs().maxCoeff());
}

/** The whole estimate of `c` (compressed; this is a global update) against `f` (full), matched
 * by entry label; dropped landmarks and object tracks (recorded poses) by ID. Returns the
 * largest relative error of the means and of the covariance. */
std::pair<double, double> compare(const CDynamicKFSLAM2D& f, const CDynamicKFSLAM2D& c,
                                  const std::string& where)
{
	Eigen::VectorXd x1, x2;
	Eigen::MatrixXd P1, P2;
	std::vector<std::string> l1, l2;
	f.getStateWithoutPads(x1, P1, &l1);
	c.getStateWithoutPads(x2, P2, &l2);
	EXPECT_EQ(c.workingDim(), c.fullMean().size()) << where << ": not expanded";
	if (l1.size() != l2.size())
	{
		ADD_FAILURE() << where << ": " << l1.size() << " vs " << l2.size() << " entries";
		return {1, 1};
	}
	std::map<std::string, int> at;
	for (size_t i = 0; i < l2.size(); ++i) at[l2[i]] = int(i);
	std::vector<int> perm;
	for (const auto& l : l1)
	{
		if (!at.count(l))
		{
			ADD_FAILURE() << where << ": " << l << " missing";
			return {1, 1};
		}
		perm.push_back(at[l]);
	}
	const double ex = relErr(x1, x2(perm)), eP = relErr(P1, P2(perm, perm));
	EXPECT_LE(ex, 1e-9) << where;
	EXPECT_LE(eP, 1e-9) << where;
	// Dropped landmarks, per ID in the order they were dropped (a landmark read again after its
	// drop is a new entry and may be dropped again).
	std::map<int32_t, std::vector<TStaticLandmarkEstimate>> d1, d2;
	for (const auto& e : f.getStaticLandmarks(true))
		if (!e.in_state) d1[e.id].push_back(e);
	for (const auto& e : c.getStaticLandmarks(true))
		if (!e.in_state) d2[e.id].push_back(e);
	EXPECT_EQ(d1.size(), d2.size()) << where;
	for (const auto& [id, v] : d1)
	{
		if (!d2.count(id) || d2[id].size() != v.size())
		{
			ADD_FAILURE() << where << ": landmark " << id << " dropped differently";
			continue;
		}
		for (size_t i = 0; i < v.size(); ++i)
		{
			EXPECT_LE((v[i].mean - d2[id][i].mean).norm(), 1e-9 * v[i].mean.norm()) << where;
			EXPECT_LE(relErr(v[i].cov, d2[id][i].cov), 1e-9) << where;
		}
	}
	const auto t1 = f.getObjectTracks(), t2 = c.getObjectTracks();
	EXPECT_EQ(t1.size(), t2.size()) << where;
	for (const auto& [obj, tr] : t1)
	{
		if (!t2.count(obj) || tr.poses.size() != t2.at(obj).poses.size())
		{
			ADD_FAILURE() << where << ": object " << obj << " track differs";
			continue;
		}
		for (size_t i = 0; i < tr.poses.size(); ++i)
			EXPECT_LE((tr.poses[i].mean - t2.at(obj).poses[i].mean).cwiseAbs().maxCoeff(), 1e-9)
			    << where;
	}
	return {ex, eP};
}

void runAndCompare(const TSteps& s, const TPolicy& p, const std::string& data)
{
	CDynamicKFSLAM2D full, atCheckpoints, neverExpanded, eager;
	configure(full, s, p, false);
	configure(atCheckpoints, s, p, true);
	configure(neverExpanded, s, p, true);
	eager.setUpdateEngine(std::make_unique<estimator::CCompressedUpdateEngine>(1, 1));
	configure(eager, s, p, true);
	ASSERT_EQ(atCheckpoints.updateEngine().name(), "compressed");
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
