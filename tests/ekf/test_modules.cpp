/** The capability modules of CDynamicKFSLAM2D (libs/ekf/src/modules, doc/architecture.md
 * "Capability modules"): the shipped profiles enable none (the step calls no module hook), each
 * option enables exactly its module, on both sides of its enabling condition, and an enabled
 * module's hooks are called once per step and hook. */
#include <dynslam/common/config_include.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/seam_registries.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tiny_scenario.h"

using namespace dynslam;
using Names = std::vector<std::string>;

namespace
{
const std::string kIni = dynslam_test::script::kFilterKeys +
                         "Sigma_0 = [1e-6 1e-6 1e-8]\n"
                         "Sigma_xi = [0.1 0.1]\n";

/** kIni with `keys` added to [DynamicKFSLAM], `classify` as the [Classify] section and the
 * step length of the object-centric models. */
std::string ini(const std::string& keys, const std::string& classify = "")
{
	return std::string(kIni) + keys + "\n[Classify]\n" + classify +
	       "\n[ObjectModel]\ncv_dt = 0.5\n[DynamicKFSLAM_KalmanFilter]\nmethod = kfEKFNaive\n";
}

Names modulesOf(const std::string& text)
{
	CDynamicKFSLAM2D f;
	mrpt::config::CConfigFileMemory c(text);
	f.loadOptions(c, "DynamicKFSLAM");
	return f.enabledModules();
}

dynslam_test::TinyScenario scenario() { return dynslam_test::makeTwoObjectScenario(12, 11); }

/** Runs the tiny scenario; returns the hook calls. */
size_t run(CDynamicKFSLAM2D& f)
{
	const auto sc = scenario();
	for (size_t k = 0; k < sc.actions.size(); ++k)
		f.processActionObservation(sc.actions[k], sc.frames[k]);
	return f.moduleHookCalls();
}
}  // namespace

TEST(Modules, ShippedProfilesEnableNoneAndTheStepCallsNoHook)
{
	for (const char* profile : {"paper.ini", "default.ini"})
	{
		const std::string path =
		    (std::filesystem::path(DYNSLAM_CONFIG_DIR) / "profiles" / profile).string();
		mrpt::config::CConfigFileMemory base(ini("")), c;
		config::overlayProfile(base, path, {"DynamicKFSLAM", "DynamicKFSLAM_KalmanFilter"}, c);
		CDynamicKFSLAM2D f;
		f.loadOptions(c, "DynamicKFSLAM");
		EXPECT_EQ(f.enabledModules(), Names{}) << profile;
		EXPECT_EQ(run(f), 0u) << profile;
		EXPECT_GT(f.getObjectTracks().size(), 0u) << profile;  // the scenario has objects
	}
}

TEST(Modules, EachOptionEnablesExactlyItsModule)
{
	EXPECT_EQ(modulesOf(ini("")), Names{});
	EXPECT_EQ(modulesOf(ini("fuse_landmarks_prob = 0.99")), Names{"landmark_fusion"});
	EXPECT_EQ(modulesOf(ini("fuse_landmarks_prob = 0")), Names{});
	EXPECT_EQ(modulesOf(ini("first_estimate_jacobians = true")), Names{"first_estimates"});
	EXPECT_EQ(modulesOf(ini("first_estimate_jacobians = false")), Names{});
	EXPECT_EQ(modulesOf(ini("drop_object_after_unseen_steps = 1")), Names{"object_drop"});
	EXPECT_EQ(modulesOf(ini("drop_object_after_unseen_steps = 0")), Names{});
	// Live merges: with a router that classifies only.
	EXPECT_EQ(modulesOf(ini("feature_labels = classify", "classify_merge_live = true")),
	          Names{"live_merge"});
	EXPECT_EQ(modulesOf(ini("feature_labels = ids", "classify_merge_live = true")), Names{});
	EXPECT_EQ(modulesOf(ini("feature_labels = classify", "classify_merge_live = false")), Names{});
	// The object-centric motion models (a velocity block): cv, ctrv, ca, mm; not the paper's.
	for (const char* model : {"cv", "ctrv", "ca", "mm"})
		EXPECT_EQ(modulesOf(ini(std::string("object_model = ") + model)), Names{"object_motion"})
		    << model;
	EXPECT_EQ(modulesOf(ini("object_model = paper")), Names{});
	EXPECT_EQ(modulesOf(ini("object_model = paper_smoothing\nSigma_s = [1e-2 1e-2 1e-3]\n"
	                        "keep_last_poses = 3")),
	          Names{});
	// Linked merges: a classifying router with an object-centric model only.
	EXPECT_EQ(modulesOf(ini("feature_labels = classify\nobject_model = cv",
	                        "classify_merge_linked = true")),
	          (Names{"object_motion", "linked_merge"}));
	EXPECT_EQ(modulesOf(ini("feature_labels = classify\nobject_model = paper",
	                        "classify_merge_linked = true")),
	          Names{});
	EXPECT_EQ(
	    modulesOf(ini("feature_labels = ids\nobject_model = cv", "classify_merge_linked = true")),
	    Names{"object_motion"});
	// Several, in the order their hooks run (fusion and object drops need feature_labels = ids).
	EXPECT_EQ(modulesOf(ini("first_estimate_jacobians = true\ndrop_object_after_unseen_steps = 3\n"
	                        "fuse_landmarks_prob = 0.99")),
	          (Names{"landmark_fusion", "first_estimates", "object_drop"}));
	EXPECT_EQ(modulesOf(ini("feature_labels = classify\nobject_model = cv\n"
	                        "first_estimate_jacobians = true",
	                        "classify_merge_linked = true\nclassify_merge_live = true")),
	          (Names{"first_estimates", "object_motion", "linked_merge", "live_merge"}));
}

TEST(Modules, HooksAreCalledOncePerStepAndHook)
{
	const size_t steps = scenario().actions.size();
	ASSERT_GT(steps, 0u);
	// fusion: AfterRoute and AfterCommit (StaticForgotten: no static landmark leaves the state
	// here, nothing drops them); first estimates: AfterPropagate and EndOfStep; object drop:
	// PlanDrops; object motion: AfterPropagate, AfterStaticUpdate, AfterMotion and PlanDrops
	// (ObjectForgotten: no object is dropped or merged here).
	const std::vector<std::pair<std::string, size_t>> cases{
	    {"fuse_landmarks_prob = 0.99", 2 * steps},
	    {"object_model = cv", 4 * steps},
	    {"first_estimate_jacobians = true", 2 * steps},
	    {"drop_object_after_unseen_steps = 100", steps},
	    {"fuse_landmarks_prob = 0.99\nfirst_estimate_jacobians = true", 4 * steps}};
	for (const auto& [keys, calls] : cases)
	{
		CDynamicKFSLAM2D f;
		mrpt::config::CConfigFileMemory c(ini(keys));
		f.loadOptions(c, "DynamicKFSLAM");
		EXPECT_EQ(run(f), calls) << keys;
		f.reset();  // a reset starts the count again
		EXPECT_EQ(f.moduleHookCalls(), 0u) << keys;
	}
}

TEST(Modules, RouterSetByTheUserMayMergeLinkedObjects)
{
	CDynamicKFSLAM2D f;
	f.setRouter(estimator::routers().make("ids", {}));
	f.reset();
	EXPECT_EQ(f.enabledModules(), Names{"linked_merge"});
	CDynamicKFSLAM2D g;
	EXPECT_EQ(g.enabledModules(), Names{});
}

TEST(Modules, OdometryBiasIsAModuleWithoutHooks)
{
	// odometry_bias != none makes the module (it owns the bias block, the first block of the
	// state); it has no hook: the step's hook calls stay 0, the bias is estimated.
	const std::string bias =
	    "[OdometryBias]\nodometry_dt = 0.5\nbias_rate_std0 = 0.05\n"
	    "bias_rate_rw = 1e-4\nbias_scale_std0 = 0.05\nbias_scale_rw = 1e-4\n"
	    "[DynamicKFSLAM]\n";
	EXPECT_EQ(modulesOf(ini("odometry_bias = none")), Names{});
	for (const std::string mode : {"rate", "rate_scale"})
	{
		CDynamicKFSLAM2D f;
		mrpt::config::CConfigFileMemory c(ini("odometry_bias = " + mode + "\n" + bias));
		f.loadOptions(c, "DynamicKFSLAM");
		EXPECT_EQ(f.enabledModules(), Names{"odometry_bias"}) << mode;
		ASSERT_FALSE(f.getLayout().empty());
		EXPECT_EQ(f.getLayout()[0].kind, estimator::BlockKind::OdometryBias);
		EXPECT_EQ(run(f), 0u) << mode;
		const auto b = f.getOdometryBias();
		ASSERT_TRUE(b.has_value()) << mode;
		EXPECT_EQ(b->first.size(), mode == "rate" ? 1 : 2);
	}
	CDynamicKFSLAM2D none;
	EXPECT_FALSE(none.getOdometryBias().has_value());
}
