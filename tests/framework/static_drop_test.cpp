/** The static drop rule (drop_static_after_unseen_steps = N) in every back-end, to the step:
 * a landmark last seen at step s is dropped at step s + N (not one step earlier or later), is
 * then listed by getDroppedStaticLandmarks() (allStaticLandmarks) as not in the state, and the step
 * report counts it. The windowed back-ends do not implement the rule (doc/backends.md,
 * Limitations): there the landmark must stay. */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam_test/scripted_steps.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "any_backend.h"

using namespace dynslam;
namespace script = dynslam_test::script;

namespace
{
const std::string kIni = dynslam_test::script::kFilterKeys +
                         "Sigma_0 = [1e-6 1e-6 1e-8]\n"
                         "Sigma_xi = [0.1 0.1]\n"
                         "drop_static_after_unseen_steps = 3\n"
                         "[Framework]\n"
                         "window_size = 4\n";

constexpr int kLastSeen = 2;     ///< landmark 7 is seen at steps 0..2
constexpr int kUnseenSteps = 3;  ///< drop_static_after_unseen_steps above
constexpr int kSteps = 9;

/** Where landmark `id` is: 1 in the state, 0 recorded as dropped, -1 nowhere. */
int whereIs(const ISlamBackend& be, int32_t id)
{
	for (const auto& l : allStaticLandmarks(be))
		if (l.id == id) return l.in_state ? 1 : 0;
	return -1;
}
}  // namespace

TEST(StaticDrop, ExactStepInEveryBackend)
{
	const std::vector<std::pair<int32_t, Eigen::Vector2d>> always{
	    {0, {6, 6}}, {1, {-6, 6}}, {2, {-6, -6}}, {3, {6, -6}}, {4, {0, 10}}};
	const Eigen::Vector2d lm7(3, -9);
	const Eigen::Vector3d u(1.0, 0.0, 0.2);
	const Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
	for (const auto& kind : dynslam_test::allBackendKinds())
	{
		SCOPED_TRACE(kind);
		auto be = dynslam_test::anyBackend(kind, kIni);
		const bool implementsRule = kind == "ekf" || kind == "alg1";
		const int dropStep = kLastSeen + kUnseenSteps;
		Eigen::Vector3d x = Eigen::Vector3d::Zero();
		for (int k = 0; k < kSteps; ++k)
		{
			if (k > 0) x = models::composePose(x, u);
			auto seen = always;
			if (k <= kLastSeen) seen.push_back({7, lm7});
			be->processActionObservation(script::action(k == 0 ? Eigen::Vector3d::Zero() : u,
			                                            k == 0 ? Eigen::Matrix3d::Zero() : U),
			                             script::frame(x, seen));
			const TStepReport& r = be->getLastStepReport();
			ASSERT_EQ(r.step, k);
			if (!implementsRule)
			{
				EXPECT_EQ(r.dropped_static, 0u) << "step " << k;
				EXPECT_EQ(whereIs(*be, 7), 1) << "step " << k;
				continue;
			}
			EXPECT_EQ(r.dropped_static, k == dropStep ? 1u : 0u) << "step " << k;
			EXPECT_EQ(whereIs(*be, 7), k < dropStep ? 1 : 0) << "step " << k;
			for (int32_t id = 0; id < 5; ++id) EXPECT_EQ(whereIs(*be, id), 1) << "step " << k;
		}
		// The recorded estimate is the landmark's last one, near the truth.
		for (const auto& l : allStaticLandmarks(*be))
		{
			if (l.id == 7)
			{
				EXPECT_LT((l.mean - lm7).norm(), 0.05);
			}
		}
	}
}
