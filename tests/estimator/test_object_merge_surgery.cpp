/** Merging a linked object (classify_merge_linked, doc/results/classification.md "Merging a linked
 * object"): the state surgery CDynamicKFSLAM2D::mergeObjects against an independent dense
 * computation by entry labels. The map x' = G(x) (N's features re-expressed in L's body frame,
 * written here from the pose-map formulas, not with the library's merge function) is
 * differentiated by a sixth-order central stencil over the whole state; every entry of the mean
 * and of the covariance after the merge must equal G(x) and J P J^T under the renaming
 * obj<N>.f<k>.t0 -> obj<L>.f<n_L + k>.t0, with N's pose and velocity entries gone and nothing else
 * changed. */
#include <dynslam/core/models/se2.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <map>

#include "core_test_utils.h"

using namespace dynslam;

namespace
{
class CMergeEkf : public CDynamicKFSLAM2D
{
public:
	using CDynamicKFSLAM2D::mergeObjects;
};

/** The shipped highway with feature_labels = classify (or ids) and object_model = cv (model:
 * "paper" for the paper's object model). */
void runHighwayCv(CDynamicKFSLAM2D& ekf, size_t steps, const std::string& labels = "classify",
                  const std::string& model = "cv")
{
	const sim::TScenarioOptions o = dynslam_test::shippedScenario("highway.ini");
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, o.noise_seed);
	mrpt::config::CConfigFileMemory cfg(dynslam_test::highwayFilterIni(
	    "feature_labels = " + labels + "\nobject_model = " + model +
	    "\n[ObjectModel]\ncv_dt = 0.5\n"
	    "cv_accel_psd = [1e-3 1e-3 1e-5]\ncv_velocity_prior_std = [0.5 0.5 0.05]\n"));
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	for (size_t k = 0; k < steps; ++k) ekf.processActionObservation(run.actions[k], run.frames[k]);
}

std::map<std::string, Eigen::Index> byLabel(const std::vector<std::string>& labels)
{
	std::map<std::string, Eigen::Index> m;
	for (size_t i = 0; i < labels.size(); ++i) m[labels[i]] = Eigen::Index(i);
	return m;
}

/** Indices of the entries whose label starts with prefix, in state order. */
std::vector<Eigen::Index> withPrefix(const std::vector<std::string>& labels, const std::string& p)
{
	std::vector<Eigen::Index> out;
	for (size_t i = 0; i < labels.size(); ++i)
		if (labels[i].rfind(p, 0) == 0) out.push_back(Eigen::Index(i));
	return out;
}

/** x' = G(x) of a merge, written from the pose-map formulas over the labelled state: N's
 * features moved to the world by N's pose (about N's founders' centroid), then into L's body
 * frame (about L's founders' centroid). */
struct TDenseMerge
{
	std::map<std::string, Eigen::Index> at;
	estimator::TObjectEntry eL, eN;
	std::string L, N;
	std::vector<Eigen::Index> xiL, xiN;
	TDenseMerge(const std::vector<std::string>& labels, const estimator::TObjectEntry& l,
	            const estimator::TObjectEntry& n, const std::string& Ls, const std::string& Ns,
	            const std::vector<Eigen::Index>& xl, const std::vector<Eigen::Index>& xn)
	    : at(byLabel(labels)), eL(l), eN(n), L(Ls), N(Ns), xiL(xl), xiN(xn)
	{
	}
	std::pair<Eigen::Index, Eigen::Index> feat(const std::string& o, int32_t k) const
	{
		const std::string f = o + ".f" + std::to_string(k) + ".t0";
		return {at.at(f + ".x"), at.at(f + ".y")};
	}
	Eigen::Vector2d pt(const Eigen::VectorXd& v, const std::string& o, int32_t k) const
	{
		const auto [i, j] = feat(o, k);
		return {v[i], v[j]};
	}
	Eigen::VectorXd operator()(const Eigen::VectorXd& v) const
	{
		Eigen::VectorXd y = v;
		Eigen::Vector2d cN = Eigen::Vector2d::Zero(), cL = Eigen::Vector2d::Zero();
		for (int k = 0; k < eN.founders; ++k)
			cN += pt(v, N, eN.feature_index[size_t(k)]) / eN.founders;
		for (int k = 0; k < eL.founders; ++k)
			cL += pt(v, L, eL.feature_index[size_t(k)]) / eL.founders;
		for (const int32_t k : eN.feature_index)
		{
			Eigen::Vector2d w = pt(v, N, k);
			if (xiN.size() >= 2) w += Eigen::Vector2d(v[xiN[0]], v[xiN[1]]);
			if (xiN.size() == 3)
				w = models::rot2(v[xiN[2]]) * (pt(v, N, k) - cN) + cN +
				    Eigen::Vector2d(v[xiN[0]], v[xiN[1]]);
			const Eigen::Vector2d tL(v[xiL[0]], v[xiL[1]]);
			Eigen::Vector2d f = w - tL;
			if (xiL.size() == 3) f = models::rot2(v[xiL[2]]).transpose() * (w - cL - tL) + cL;
			const auto [i, j] = feat(N, k);
			y[i] = f[0];
			y[j] = f[1];
		}
		return y;
	}
};

/** Merges `from` into `into` and checks every entry against the dense computation. poseTag
 * selects the poses the merge uses (paper model: "<step>.", the poses of this step). */
void checkMerge(CMergeEkf& ekf, int32_t from, int32_t into, const std::string& poseTag = "")
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	std::vector<std::string> labels;
	ekf.getStateWithoutPads(x, P, &labels);
	const auto& reg = ekf.router().registry();
	const estimator::TObjectEntry eL = reg.at(into), eN = reg.at(from);
	const std::string L = "obj" + std::to_string(into), N = "obj" + std::to_string(from);
	const std::vector<Eigen::Index> xiL = withPrefix(labels, L + ".xi" + poseTag),
	                                xiN = withPrefix(labels, N + ".xi" + poseTag);
	ASSERT_TRUE(xiL.size() == 2 || xiL.size() == 3);
	const TDenseMerge G{labels, eL, eN, L, N, xiL, xiN};
	const Eigen::VectorXd xe = G(x);
	const Eigen::MatrixXd J = core_test::numericJacobianHO(G, x);
	const Eigen::MatrixXd Pe = J * P * J.transpose();
	// The expected label of every entry that stays.
	std::map<std::string, Eigen::Index> expected;
	for (size_t i = 0; i < labels.size(); ++i)
	{
		std::string l = labels[i];
		if (l.rfind(N + ".xi", 0) == 0 || l.rfind(N + ".v", 0) == 0) continue;  // removed
		for (size_t k = 0; k < eN.feature_index.size(); ++k)
		{
			const std::string f = N + ".f" + std::to_string(eN.feature_index[k]) + ".t0";
			if (l.rfind(f, 0) == 0)
				l = L + ".f" + std::to_string(eL.feature_ids.size() + k) + ".t0" +
				    l.substr(f.size());
		}
		expected[l] = Eigen::Index(i);
	}
	ASSERT_TRUE(ekf.mergeObjects(from, into));
	Eigen::VectorXd x2;
	Eigen::MatrixXd P2;
	std::vector<std::string> labels2;
	ekf.getStateWithoutPads(x2, P2, &labels2);
	ASSERT_EQ(labels2.size(), expected.size());
	const double scale = std::max(1.0, Pe.cwiseAbs().maxCoeff());
	double worst = 0;
	std::vector<Eigen::Index> was;
	for (const std::string& l : labels2)
	{
		ASSERT_TRUE(expected.count(l)) << l << " after the merge has no entry before";
		was.push_back(expected.at(l));
	}
	for (size_t i = 0; i < labels2.size(); ++i)
	{
		EXPECT_NEAR(x2[Eigen::Index(i)], xe[was[i]], 1e-9) << labels2[i];
		for (size_t j = 0; j < labels2.size(); ++j)
			worst = std::max(
			    worst, std::abs(P2(Eigen::Index(i), Eigen::Index(j)) - Pe(was[i], was[j])) / scale);
	}
	EXPECT_LT(worst, 1e-10);
	core_test::reportWorst("merge covariance error (relative to the largest entry)", worst);
	EXPECT_FALSE(ekf.router().registry().has(from));
	EXPECT_EQ(ekf.router().registry().at(into).feature_ids.size(),
	          eL.feature_ids.size() + eN.feature_ids.size());
	EXPECT_EQ(ekf.router().registry().at(into).founders, eL.founders);
}

/** The objects of the run that have a velocity, with their pose dimension. */
std::map<int32_t, int> objectsWithVelocity(const CDynamicKFSLAM2D& ekf)
{
	std::map<int32_t, int> out, dim;
	for (const auto& b : ekf.getLayout().blocks())
	{
		if (b.kind == estimator::BlockKind::ObjectPose) dim[b.object] = b.dim;
		if (b.kind == estimator::BlockKind::ObjectVelocity) out[b.object] = 0;
	}
	for (auto& [o, d] : out) d = dim.at(o);
	return out;
}
}  // namespace

TEST(ObjectMergeSurgery, EveryEntryEqualsTheDenseComputation)
{
	// Objects with poses and velocities (N's pose and velocity leave the state), both ways; an
	// object without a velocity cannot take a merge (false, nothing changed).
	for (const bool reverse : {false, true})
	{
		CMergeEkf ekf;
		runHighwayCv(ekf, 30);
		const std::map<int32_t, int> objs = objectsWithVelocity(ekf);
		ASSERT_GE(objs.size(), 2u);
		std::vector<int32_t> rigid;
		for (const auto& [o, d] : objs)
			if (d == 3) rigid.push_back(o);
		ASSERT_GE(rigid.size(), 2u);
		SCOPED_TRACE(reverse ? "reverse" : "forward");
		checkMerge(ekf, rigid[reverse ? 1 : 0], rigid[reverse ? 0 : 1]);
	}
}

TEST(ObjectMergeSurgery, PaperModelLiveMergeEqualsTheDenseComputation)
{
	// classify_merge_live with the paper's model: B's f_0 (in B's first-sighting frame) are
	// brought to now by xi_B,t and into A's first-sighting frame by xi_A,t^-1; B's poses leave.
	CMergeEkf ekf;
	runHighwayCv(ekf, 30, "classify", "paper");
	const int step = ekf.getLastStepReport().step;
	std::map<int32_t, int> now;  // objects with a pose of this step -> its dimension
	for (const auto& b : ekf.getLayout().blocks())
		if (b.kind == estimator::BlockKind::ObjectPose && b.step == step) now[b.object] = b.dim;
	std::vector<int32_t> rigid;
	int32_t old = -1;
	for (const auto& [o, d] : now)
		if (d == 3) rigid.push_back(o);
	for (const auto& b : ekf.getLayout().blocks())
		if (b.kind == estimator::BlockKind::ObjectPose && !now.count(b.object)) old = b.object;
	ASSERT_GE(rigid.size(), 2u);
	// An object without a pose of this step cannot be merged with the paper's model.
	if (old >= 0)
	{
		EXPECT_FALSE(ekf.mergeObjects(old, rigid[0]));
	}
	checkMerge(ekf, rigid[1], rigid[0], std::to_string(step) + ".");
}

TEST(ObjectMergeSurgery, BadMergesChangeNothing)
{
	// The ID-range router cannot merge; an unknown object, or an object into itself, is an error:
	// each throws std::logic_error with the state unchanged.
	for (const char* labels : {"ids", "classify"})
	{
		SCOPED_TRACE(labels);
		CMergeEkf ekf;
		runHighwayCv(ekf, 30, labels);
		const std::map<int32_t, int> objs = objectsWithVelocity(ekf);
		ASSERT_GE(objs.size(), 2u);
		const int32_t a = objs.begin()->first, b = std::next(objs.begin())->first;
		Eigen::VectorXd x, x2;
		Eigen::MatrixXd P, P2;
		ekf.getStateWithoutPads(x, P);
		if (std::string(labels) == "ids")
		{
			EXPECT_THROW(ekf.mergeObjects(a, b), std::logic_error);
		}
		EXPECT_THROW(ekf.mergeObjects(a, a), std::logic_error);
		EXPECT_THROW(ekf.mergeObjects(a, 9999), std::logic_error);
		ekf.getStateWithoutPads(x2, P2);
		EXPECT_EQ(x2, x);
		EXPECT_EQ(P2, P);
		EXPECT_TRUE(ekf.router().registry().has(a));
	}
}
