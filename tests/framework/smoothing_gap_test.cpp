/** Smoothing (Alg. 6) only on three object poses of consecutive steps: an object unseen for
 * one step has no pose at that step, and the smoothing residual s(xi_{t-2}, xi_{t-1}, xi_t)
 * must not be applied to the last three poses it has when they are not t-2, t-1, t. Checked
 * in every back-end through its step report (smoothing_updates). */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/core/landmark_ids.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>

#include <set>

#include "any_backend.h"

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const std::string kIni = dynslam_test::script::kFilterKeys +
                         "Sigma_0 = [1e-6 1e-6 1e-8]\n"
                         "Sigma_xi = [1e-3 1e-3]\n"
                         "smoothing = true\n"
                         "Sigma_s = [1e-2 1e-2 1e-3]\n"
                         "keep_last_poses = 3\n"
                         "[Framework]\n"
                         "window_size = 4\n";

constexpr int kSteps = 10;
constexpr int kUnseen = 4;  ///< the object is not seen at this step

/** The object's three features at step k (rigid: translating and turning). */
script::TSeen objectAt(int k)
{
	const Eigen::Vector2d c(2 + 0.3 * k, 4);
	const Eigen::Matrix2d R = models::rot2(0.05 * k);
	const Eigen::Vector2d off[3] = {{1, 0}, {-0.5, 0.8}, {-0.5, -0.8}};
	script::TSeen s;
	for (int f = 0; f < 3; ++f) s.push_back({ids::objectFeatureId(0, f), c + R * off[f]});
	return s;
}
}  // namespace

TEST(SmoothingGap, OnlyOnConsecutiveSteps)
{
	// First sighting at step 0 (its time 0: no pose); poses at 1, 2, 3, 5, 6, ... Consecutive
	// triples end at steps 3, 7, 8, 9; at 5 (poses 2, 3, 5) and 6 (3, 5, 6) they do not.
	const std::set<int> smoothedAt{3, 7, 8, 9};
	const script::TSeen statics{
	    {0, {6, 6}}, {1, {-6, 6}}, {2, {-6, -6}}, {3, {6, -6}}, {4, {0, 10}}};
	const Eigen::Vector3d u(0.5, 0.0, 0.1);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		// cubeslam has no object-pose variables (body poses only) and no smoothing term.
		if (kind == "cubeslam") continue;
		SCOPED_TRACE(kind);
		auto be = dynslam_test::anyBackend(kind, kIni);
		Eigen::Vector3d x = Eigen::Vector3d::Zero();
		size_t total = 0;
		for (int k = 0; k < kSteps; ++k)
		{
			if (k > 0) x = models::composePose(x, u);
			script::TSeen seen = statics;
			if (k != kUnseen)
				for (const auto& s : objectAt(k)) seen.push_back(s);
			be->processActionObservation(script::action(k == 0 ? Eigen::Vector3d::Zero() : u,
			                                            k == 0 ? Eigen::Matrix3d::Zero() : U),
			                             script::frame(x, seen));
			const TStepReport& r = be->getLastStepReport();
			EXPECT_EQ(r.object_poses_added, (k == 0 || k == kUnseen) ? 0u : 1u) << "step " << k;
			EXPECT_EQ(r.smoothing_updates, smoothedAt.count(k) ? 1u : 0u) << "step " << k;
			total += r.smoothing_updates;
		}
		EXPECT_EQ(total, smoothedAt.size());
	}
}
