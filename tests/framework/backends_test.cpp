/** The back-ends of Section III as configurations (makeBackend): every kind runs on a short
 * highway, its ego, map and object-pose errors against the ground truth are small, and bad
 * options are rejected. */
#include <dynslam/core/models/se2.h>
#include <dynslam/framework/CWindowBackend.h>
#include <dynslam/framework/backend_factory.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <iostream>

#include "backends_ini.h"

using namespace dynslam;
using namespace dynslam::framework;

namespace
{
const char* const kIni = dynslam_test::kBackendsIni;

struct TErrors
{
	double ego = 0, map = 0, pose = 0;
	size_t poses = 0;
};

TErrors run(const std::string& kind, int steps, const std::string& extra = "")
{
	sim::TScenarioOptions so = sim::loadScenario(std::string(DYNSLAM_CONFIG_DIR) + "/highway.ini");
	so.steps = steps;
	const io::TGroundTruth gt = sim::buildGroundTruth(so);
	const auto r = sim::simulateMeasurements(gt, so, 7);
	mrpt::config::CConfigFileMemory ini(std::string(kIni) + extra);
	auto be = makeBackend(kind, ini, "Framework");
	TErrors e;
	for (size_t k = 0; k < r.actions.size(); ++k)
	{
		be->processActionObservation(r.actions[k], r.frames[k]);
		const auto p = be->getEgoPose();
		e.ego = std::max(e.ego, std::hypot(p.mean.x() - gt.ego[k][0], p.mean.y() - gt.ego[k][1]));
		EXPECT_TRUE(p.cov.asEigen().allFinite());
	}
	for (const auto& l : allStaticLandmarks(*be))
		e.map = std::max(e.map, (l.mean - gt.landmarks.at(l.id)).norm());
	for (const auto& [obj, tr] : be->getObjectTracks())
		for (const auto& p : tr.poses)
		{
			const Eigen::Vector3d& t = gt.objects.at(size_t(obj)).pose.at(size_t(p.step));
			e.pose = std::max(e.pose, (p.mean.head<2>() - t.head<2>()).norm());
			EXPECT_TRUE(p.cov.allFinite());
			++e.poses;
		}
	if (const auto* w = dynamic_cast<const CWindowBackend*>(be.get()))
	{
		std::cout << "[backend] " << kind << ": " << w->lastIterations()
		          << " GN iterations at the last step, " << w->cost().totalDim() << " unknowns\n";
		EXPECT_LT(w->lastIterations(), 10) << kind << ": GN did not converge in max_iterations";
	}
	std::cout << "[backend] " << kind << ": max ego error " << e.ego << " m, max landmark error "
	          << e.map << " m, max object translation error " << e.pose << " m over " << e.poses
	          << " poses\n";
	return e;
}
}  // namespace

TEST(Backends, EveryKindRunsOnTheHighway)
{
	// Thresholds about 3x the measured worst case over the kinds (2026-11-24, seed 7, 30
	// steps): ego 0.0107 m, landmark 0.0098 m, object translation 0.0169 m
	// (clusterslam_semidecoupled; the others 0.0160-0.0164 m); 60 poses (bookkeeping: exact).
	for (const auto& kind : backendKinds())
	{
		const TErrors e = run(kind, 30);
		EXPECT_LT(e.ego, 0.032) << kind;
		EXPECT_LT(e.map, 0.03) << kind;
		EXPECT_EQ(e.poses, 60u) << kind;
		EXPECT_LT(e.pose, 0.05) << kind;
	}
}

TEST(Backends, OptionVariantsRun)
{
	// pose-space residual with the dense solver, the sparse solver, a window of one pose.
	// Measured (20 steps): ego 0.0067 m, landmark 0.0096 m, object translation 0.0105 m for
	// all three; 40 poses. Thresholds about 3x.
	for (const auto& [kind, extra] : std::vector<std::pair<std::string, std::string>>{
	         {"dynaslam2", "pose_residual = pose_space\nsolver = dense\n"},
	         {"vdo", "solver = sparse\n"},
	         {"cubeslam", "window_size = 1\n"}})
	{
		const TErrors e = run(kind, 20, extra);
		EXPECT_LT(e.ego, 0.02) << kind << " " << extra;
		EXPECT_LT(e.map, 0.03) << kind << " " << extra;
		EXPECT_LT(e.pose, 0.032) << kind << " " << extra;
		EXPECT_EQ(e.poses, 40u) << kind << " " << extra;
	}
}

TEST(Backends, BadOptions)
{
	mrpt::config::CConfigFileMemory ini(std::string(kIni) + "backend = vdo\n");
	EXPECT_THROW(makeBackend("dynaslam2", ini, "Framework"), std::invalid_argument);
	TBackendOptions o = defaultBackendOptions("dynaslam2");
	o.window_size = 0;
	EXPECT_THROW(makeBackend(o), std::invalid_argument);
	EXPECT_THROW(defaultBackendOptions("orb"), std::invalid_argument);
	// drop would leave the object poses unobservable: rejected with a reason.
	mrpt::config::CConfigFileMemory drop(std::string(kIni) + "object_features = drop\n");
	EXPECT_THROW(makeBackend("dynaslam2", drop, "Framework"), std::invalid_argument);
	mrpt::config::CConfigFileMemory bad(std::string(kIni) + "pose_residual = both\n");
	EXPECT_THROW(makeBackend("vdo", bad, "Framework"), std::invalid_argument);
	// The odometry bias block is the dynamic EKF's only (issue 17): a clear error here.
	for (const char* kind : {"dynaslam2", "vdo"})
	{
		TBackendOptions b = defaultBackendOptions(kind);
		b.model.Sigma_0 = Eigen::Matrix3d::Identity() * 1e-6;  // valid otherwise
		EXPECT_NO_THROW(makeBackend(b)) << kind;
		b.model.odometry_bias.mode = "rate";
		try
		{
			makeBackend(b);
			ADD_FAILURE() << kind << ": odometry_bias = rate accepted";
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("odometry_bias = rate"), std::string::npos)
			    << e.what();
		}
		// So is the classification of anonymous tracks (issue 12): never silently ID ranges.
		b.model.odometry_bias.mode = "none";
		b.model.feature_labels = "classify";
		try
		{
			makeBackend(b);
			ADD_FAILURE() << kind << ": feature_labels = classify accepted";
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("feature_labels = classify"), std::string::npos)
			    << e.what();
		}
		// The anchored prior (prior_gauge = anchor, issue 13) is the dynamic EKF's only.
		b.model.feature_labels = "ids";
		b.model.prior_gauge_anchor = true;
		try
		{
			makeBackend(b);
			ADD_FAILURE() << kind << ": prior_gauge = anchor accepted";
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("prior_gauge = anchor"), std::string::npos)
			    << e.what();
		}
	}
}
