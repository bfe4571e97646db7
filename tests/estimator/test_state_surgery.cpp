/** State surgery (feature_labels = classify, doc/results/classification.md): a static landmark that
 * turns out to be moving becomes its object's f_0 in place. Checked against an independent
 * dense bookkeeping by entry labels: every entry of the state and of the covariance after the
 * surgery equals the entry before it under the renaming lm<id> -> obj<o>.f<k>.t0, nothing else
 * changes, and a bad conversion list changes nothing. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <map>

using namespace dynslam;

namespace
{
/** The EKF with its surgery reachable from the test. */
class CSurgeryEkf : public CDynamicKFSLAM2D
{
public:
	using CDynamicKFSLAM2D::convertStaticLandmarks;
};

struct TSnapshot
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	std::vector<std::string> labels;
};

TSnapshot snapshot(const CDynamicKFSLAM2D& ekf)
{
	TSnapshot s;
	ekf.getStateWithoutPads(s.x, s.P, &s.labels);
	return s;
}

/** Runs the labelled EKF `steps` steps on the shipped highway scenario. */
void runHighway(CDynamicKFSLAM2D& ekf, size_t steps)
{
	const sim::TScenarioOptions o =
	    sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/highway.ini");
	const io::TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, o.noise_seed);
	mrpt::config::CConfigFileMemory cfg(
	    "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-5 1e-5]\n"
	    "motion_noise = action\nSigma_0 = [1e-5 1e-5 1e-7]\nSigma_xi = [0.1 0.1]\n"
	    "[DynamicKFSLAM_KalmanFilter]\nmethod = kfEKFNaive\n");
	ekf.loadOptions(cfg, "DynamicKFSLAM");
	for (size_t k = 0; k < steps; ++k) ekf.processActionObservation(run.actions[k], run.frames[k]);
}
}  // namespace

TEST(StateSurgery, ConvertedLandmarksKeepTheirEntriesAndNothingElseChanges)
{
	CSurgeryEkf ekf;
	runHighway(ekf, 30);
	const std::vector<TStaticLandmarkEstimate> lms = ekf.getStaticLandmarks();
	ASSERT_GE(lms.size(), 4u);
	const int32_t a = lms[1].id, b = lms[3].id;
	const TSnapshot before = snapshot(ekf);
	ekf.convertStaticLandmarks({{a, 900, 0}, {b, 900, 1}});
	const TSnapshot after = snapshot(ekf);

	// The dense bookkeeping: the expected label of every entry before, then the entries after
	// looked up by label.
	const std::map<std::string, std::string> rename{
	    {"lm" + std::to_string(a) + ".x", "obj900.f0.t0.x"},
	    {"lm" + std::to_string(a) + ".y", "obj900.f0.t0.y"},
	    {"lm" + std::to_string(b) + ".x", "obj900.f1.t0.x"},
	    {"lm" + std::to_string(b) + ".y", "obj900.f1.t0.y"}};
	std::map<std::string, Eigen::Index> was;
	for (Eigen::Index i = 0; i < Eigen::Index(before.labels.size()); ++i)
	{
		const auto it = rename.find(before.labels[size_t(i)]);
		was[it == rename.end() ? before.labels[size_t(i)] : it->second] = i;
	}
	ASSERT_EQ(after.labels.size(), before.labels.size());
	ASSERT_EQ(after.x.size(), before.x.size());
	std::vector<Eigen::Index> from;
	size_t renamed = 0;
	for (Eigen::Index i = 0; i < after.x.size(); ++i)
	{
		const std::string& l = after.labels[size_t(i)];
		ASSERT_TRUE(was.count(l)) << "entry " << l << " after the surgery has no entry before";
		from.push_back(was.at(l));
		renamed += l.rfind("obj900.", 0) == 0 ? 1 : 0;
	}
	EXPECT_EQ(renamed, 4u);
	for (Eigen::Index i = 0; i < after.x.size(); ++i)
	{
		EXPECT_EQ(after.x[i], before.x[from[size_t(i)]]) << after.labels[size_t(i)];
		for (Eigen::Index j = 0; j < after.x.size(); ++j)
			ASSERT_EQ(after.P(i, j), before.P(from[size_t(i)], from[size_t(j)]))
			    << after.labels[size_t(i)] << ", " << after.labels[size_t(j)];
	}
	// The landmarks left the static map; the others stayed.
	const std::vector<TStaticLandmarkEstimate> now = ekf.getStaticLandmarks();
	EXPECT_EQ(now.size(), lms.size() - 2);
	for (const auto& l : now) EXPECT_TRUE(l.id != a && l.id != b);
	EXPECT_EQ(ekf.getLastStepReport().converted_static, 2u);
}

TEST(StateSurgery, BadConversionListsChangeNothing)
{
	CSurgeryEkf ekf;
	runHighway(ekf, 20);
	const std::vector<TStaticLandmarkEstimate> lms = ekf.getStaticLandmarks();
	ASSERT_GE(lms.size(), 2u);
	const TSnapshot before = snapshot(ekf);
	// A landmark not in the state, after a good one; a landmark listed twice.
	EXPECT_THROW(ekf.convertStaticLandmarks({{lms[0].id, 5, 0}, {99999, 5, 1}}), std::logic_error);
	EXPECT_THROW(ekf.convertStaticLandmarks({{lms[0].id, 5, 0}, {lms[0].id, 5, 1}}),
	             std::logic_error);
	const TSnapshot after = snapshot(ekf);
	EXPECT_EQ(after.labels, before.labels);
	EXPECT_EQ(after.x, before.x);
	EXPECT_EQ(after.P, before.P);
	EXPECT_EQ(ekf.getStaticLandmarks().size(), lms.size());
}
