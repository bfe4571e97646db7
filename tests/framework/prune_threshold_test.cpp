/** Pruning of static landmarks (prune_min_sightings = k, prune_window = N; issue 29, item 2),
 * to the step, in the back-ends that drop (the EKF and Alg. 1): a landmark read in exactly k of
 * the first N steps after it was added stays; one read in k - 1 of them is removed at the end of
 * the window's last step (its k-th reading one step later is a new landmark with a window of its
 * own), recorded or forgotten per record_dropped, and counted in TStepReport::pruned_static.
 * The windowed back-ends do not implement it and reject the keys. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/common/model_options.h>
#include <dynslam/estimator/drop_policy.h>
#include <dynslam_test/option_errors.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "any_backend.h"

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const std::string kBase =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-4 1e-4]\n"
    "motion_noise = action\n"
    "Sigma_0 = [1e-6 1e-6 1e-8]\n"
    "Sigma_xi = [0.1 0.1]\n"
    "prune_min_sightings = 3\n"
    "prune_window = 5\n";
const std::string kFramework = "[Framework]\nwindow_size = 4\n";
constexpr int kSteps = 10;

/** The steps at which each landmark besides the anchors 0..4 is read. */
const std::map<int32_t, std::set<int>> kReadAt{
    {7, {0, 2, 4}},        // exactly k = 3 in its window 0..4: stays
    {8, {0, 2, 5}},        // k - 1 in 0..4 (the third at 5, outside): pruned at 4; new at 5,
                           // read once in 5..9: pruned again at 9
    {9, {3, 4, 5, 6, 7}},  // 5 in 3..7: stays
    {10, {3}}};            // 1 in 3..7: pruned at 7
const std::map<int, std::vector<int32_t>> kPrunedAt{{4, {8}}, {7, {10}}, {9, {8}}};
const std::map<int32_t, Eigen::Vector2d> kWhere{
    {7, {3, -9}}, {8, {8, 9}}, {9, {12, -7}}, {10, {15, 8}}};

/** Where landmark `id` is: 1 in the state, 0 recorded as dropped, -1 nowhere. */
int whereIs(const ISlamBackend& be, int32_t id)
{
	for (const auto& l : allStaticLandmarks(be))
		if (l.id == id) return l.in_state ? 1 : 0;
	return -1;
}

void runScript(ISlamBackend& be, bool recorded)
{
	const script::TSeen anchors{
	    {0, {6, 6}}, {1, {-6, 6}}, {2, {-6, -6}}, {3, {6, -6}}, {4, {0, 10}}};
	const Eigen::Vector3d u(1.0, 0.0, 0.05);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	Eigen::Vector3d x = Eigen::Vector3d::Zero();
	std::map<int32_t, int> state;  // expected: 1 in the state, 0 pruned, -1 never seen
	for (const auto& [id, at] : kReadAt) state[id] = -1;
	for (int k = 0; k < kSteps; ++k)
	{
		if (k > 0) x = models::composePose(x, u);
		script::TSeen seen = anchors;
		for (const auto& [id, at] : kReadAt)
			if (at.count(k))
			{
				seen.push_back({id, kWhere.at(id)});
				state[id] = 1;
			}
		be.processActionObservation(script::action(k == 0 ? Eigen::Vector3d::Zero() : u,
		                                           k == 0 ? Eigen::Matrix3d::Zero() : U),
		                            script::frame(x, seen));
		const TStepReport& r = be.getLastStepReport();
		ASSERT_EQ(r.step, k);
		const auto pruned = kPrunedAt.find(k);
		const size_t expected = pruned == kPrunedAt.end() ? 0 : pruned->second.size();
		EXPECT_EQ(r.pruned_static, expected) << "step " << k;
		EXPECT_EQ(r.dropped_static, 0u) << "step " << k;
		if (pruned != kPrunedAt.end())
			for (const int32_t id : pruned->second) state[id] = 0;
		for (const auto& [id, s] : state)
		{
			const int want = s == 0 && !recorded ? -1 : s;
			EXPECT_EQ(whereIs(be, id), want) << "landmark " << id << ", step " << k;
		}
		for (int32_t id = 0; id < 5; ++id) EXPECT_EQ(whereIs(be, id), 1) << "step " << k;
	}
}
}  // namespace

TEST(Prune, ExactlyKSightingsInTheWindowStayKMinusOneArePrunedAtTheWindowsEnd)
{
	for (const std::string kind : {"ekf", "alg1"})
		for (const bool recorded : {true, false})
		{
			SCOPED_TRACE(kind + (recorded ? " recorded" : " forgotten"));
			auto be = dynslam_test::anyBackend(
			    kind, kBase + (recorded ? "" : "record_dropped = false\n") + kFramework);
			runScript(*be, recorded);
		}
}

TEST(Prune, OffByDefaultNothingIsPruned)
{
	std::string ini = kBase;
	ini.replace(ini.find("prune_min_sightings = 3\n"), 24, "");
	ini.replace(ini.find("prune_window = 5\n"), 17, "");
	auto be = dynslam_test::anyBackend("ekf", ini + kFramework);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	for (int k = 0; k < kSteps; ++k)
	{
		script::TSeen seen{{0, {6, 6}}, {1, {-6, 6}}};
		if (k == 0) seen.push_back({10, {15, 8}});  // read once
		be->processActionObservation(script::action(Eigen::Vector3d(0.5, 0, 0), U),
		                             script::frame(Eigen::Vector3d(0.5 * k, 0, 0), seen));
		EXPECT_EQ(be->getLastStepReport().pruned_static, 0u);
	}
	EXPECT_EQ(whereIs(*be, 10), 1);
}

TEST(Prune, WindowedBackendsRejectTheKeys)
{
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		if (kind == "ekf" || kind == "alg1") continue;
		SCOPED_TRACE(kind);
		try
		{
			dynslam_test::anyBackend(kind, kBase + kFramework);
			ADD_FAILURE() << "no error";
		}
		catch (const std::invalid_argument& e)
		{
			const std::string m = e.what();
			EXPECT_NE(m.find("prune_min_sightings"), std::string::npos) << m;
			EXPECT_NE(m.find("alg1"), std::string::npos) << m;
		}
	}
}

TEST(Prune, BadKeysAreClearErrors)
{
	const std::string head =
	    "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-4 1e-4]\n";
	const std::vector<std::pair<std::string, std::vector<std::string>>> bad{
	    {"prune_min_sightings = 3\nprune_window = 0\n",
	     {"prune_window = 0", "prune_min_sightings = 3", ">= 1"}},
	    {"prune_min_sightings = 3\n", {"prune_window = 0", "prune_min_sightings = 3"}},
	    {"prune_min_sightings = -1\nprune_window = 5\n", {"prune_min_sightings = -1", ">= 0"}},
	    {"prune_min_sightings = 3\nprune_window = -2\n", {"prune_window = -2", ">= 0"}},
	    {"prune_window = 5\n", {"prune_window = 5", "prune_min_sightings = 0"}},
	    {"prune_min_sightings = 1\nprune_window = 5\n", {"prune_min_sightings = 1", ">= 2"}},
	    {"prune_min_sightings = 6\nprune_window = 5\n",
	     {"prune_min_sightings = 6", "prune_window = 5", "every landmark"}}};
	for (const auto& [keys, words] : bad)
	{
		std::vector<std::string> all{"[DynamicKFSLAM]"};
		all.insert(all.end(), words.begin(), words.end());
		dynslam_test::expectOptionsError(head + keys, all);
	}
	// The boundary cases that are valid: k = 2, and k = N.
	for (const std::string keys : {"prune_min_sightings = 2\nprune_window = 5\n",
	                               "prune_min_sightings = 5\nprune_window = 5\n"})
	{
		mrpt::config::CConfigFileMemory c(head + keys);
		TModelOptions o;
		EXPECT_NO_THROW(o.loadFromConfigFile(c, "DynamicKFSLAM")) << keys;
	}
}

TEST(Prune, DropPolicyWindowBoundaries)
{
	estimator::TDropOptions o;
	o.prune_min_sightings = 3;
	o.prune_window = 5;  // steps 10..14 for a landmark first read at 10
	estimator::CDropPolicy d(o);
	for (const int s : {10, 12, 14}) d.noteSeen(1, s);  // exactly 3: stays
	for (const int s : {10, 12, 15}) d.noteSeen(2, s);  // 2 inside, the third outside
	for (const int s : {10, 11, 12, 13}) d.noteSeen(3, s);
	for (int step = 10; step < 14; ++step)
		for (const int32_t id : {1, 2, 3}) EXPECT_FALSE(d.pruneDue(id, step, 10)) << step;
	EXPECT_FALSE(d.pruneDue(1, 14, 10));
	EXPECT_TRUE(d.pruneDue(2, 14, 10));  // decided at the end of the window's last step
	EXPECT_FALSE(d.pruneDue(3, 14, 10));
	EXPECT_FALSE(d.pruneDue(1, 1000, 10));  // the count is final once the window is over
	EXPECT_TRUE(d.due(2, 14, 10));
	EXPECT_FALSE(d.staticDue(2, 14, 10));  // the unseen rule is off
	// Never noted: the window starts at addedStep, no reading counted.
	EXPECT_FALSE(d.pruneDue(9, 13, 10));
	EXPECT_TRUE(d.pruneDue(9, 14, 10));
	// Forgotten (left the state) and read again: a new window.
	d.forget(2);
	d.noteSeen(2, 20);
	EXPECT_FALSE(d.pruneDue(2, 23, 20));
	EXPECT_TRUE(d.pruneDue(2, 24, 20));
	// Off: never.
	EXPECT_FALSE(estimator::CDropPolicy().pruneDue(9, 1000, 0));
}
