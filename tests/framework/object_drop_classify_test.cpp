/** drop_object_after_unseen_steps with feature_labels = classify (issue 29, items 1-2): the
 * object of anonymous tracks that are unseen for N steps leaves the state, and when those tracks
 * are read again they restart as new candidates under fresh IDs (TRoutedStep::restarted) and
 * form a new object once decided moving; none of their readings reaches the dropped object.
 * Without the drop the same readings are the old object's (time t). */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/model_options.h>
#include <dynslam_test/option_errors.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <set>

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const std::string kIni =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-4 1e-4]\n"
    "motion_noise = action\n"
    "Sigma_0 = [1e-6 1e-6 1e-8]\n"
    "Sigma_xi = [1e-2 1e-2]\n"
    "feature_labels = classify\n";
constexpr int kSteps = 14;
/** The car (tracks 100-102) is read at steps 0..3 and 9..13 (unseen 4..8). */
bool carSeen(int k) { return k <= 3 || k >= 9; }

struct TStep
{
	TStepReport report;
	estimator::TRoutedStep routed;
};

std::vector<TStep> run(const std::string& extra)
{
	CDynamicKFSLAM2D f;
	f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	mrpt::config::CConfigFileMemory c(kIni + extra);
	f.loadOptions(c);
	const script::TSeen statics{{0, {6, 6}}, {1, {-6, 6}}, {2, {-6, -6}}, {3, {6, -6}}};
	const Eigen::Vector2d off[3] = {{1.2, 0}, {-0.6, 0.9}, {-0.6, -0.9}};
	const Eigen::Vector3d u(0.5, 0.0, 0.05);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	std::vector<TStep> out;
	for (int k = 0; k < kSteps; ++k)
	{
		if (k > 0) x = models::composePose(x, u);
		script::TSeen s = statics;
		const Eigen::Vector2d car(2 + 1.0 * k, 5);  // 1 m per step
		if (carSeen(k))
			for (int i = 0; i < 3; ++i) s.push_back({100 + i, car + off[i]});
		f.processActionObservation(script::action(k == 0 ? Eigen::Vector3d::Zero() : u,
		                                          k == 0 ? Eigen::Matrix3d::Zero() : U),
		                           script::frame(x, s));
		out.push_back({f.getLastStepReport(), f.lastRoutedStep()});
	}
	return out;
}

/** The objects the step's readings went to. */
std::set<int32_t> objectsRead(const estimator::TRoutedStep& r)
{
	std::set<int32_t> o;
	for (const auto& m : r.readings)
		if (m.object >= 0) o.insert(m.object);
	return o;
}
}  // namespace

TEST(ObjectDropClassify, DroppedObjectsTracksRestartAsANewObject)
{
	const std::vector<TStep> with = run("drop_object_after_unseen_steps = 3\n");
	const std::vector<TStep> without = run("");
	// The car is decided moving within its first four sightings in both runs: one object.
	const std::set<int32_t> before = objectsRead(with[3].routed);
	ASSERT_EQ(before.size(), 1u);
	ASSERT_EQ(objectsRead(without[3].routed), before);
	const int32_t car = *before.begin();
	size_t dropped = 0;
	for (int k = 0; k < kSteps; ++k) dropped += with[size_t(k)].report.dropped_objects;
	EXPECT_EQ(dropped, 1u);
	// Step 9: the three tracks are read again. With the drop they restart (fresh candidates, no
	// reading for the dropped object, none skipped as a dropped object's); without it they are
	// the old object's readings.
	EXPECT_EQ(with[9].routed.restarted, 3u);
	EXPECT_EQ(with[9].report.skipped_dropped_object, 0u);
	EXPECT_EQ(without[9].routed.restarted, 0u);
	EXPECT_EQ(objectsRead(without[9].routed), before);
	std::set<int32_t> after;
	for (int k = 9; k < kSteps; ++k)
	{
		EXPECT_EQ(objectsRead(with[size_t(k)].routed).count(car), 0u) << "step " << k;
		for (const int32_t o : objectsRead(with[size_t(k)].routed)) after.insert(o);
	}
	// Decided moving again: one new object, not the dropped one.
	ASSERT_EQ(after.size(), 1u);
	EXPECT_NE(*after.begin(), car);
}

TEST(ObjectDropClassify, BoxesAreRejectedClassifyAccepted)
{
	const std::string head = "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1 1]\n";
	{
		mrpt::config::CConfigFileMemory c(
		    head + "drop_object_after_unseen_steps = 3\nfeature_labels = classify\n");
		TModelOptions o;
		EXPECT_NO_THROW(o.loadFromConfigFile(c, "DynamicKFSLAM"));
	}
	dynslam_test::expectOptionsError(
	    head + "drop_object_after_unseen_steps = 3\nfeature_labels = boxes\n",
	    {"drop_object_after_unseen_steps", "ids and classify"});
}
