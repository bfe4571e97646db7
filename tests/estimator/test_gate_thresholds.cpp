/** The gates of the static update and the drop policy on both sides of their boundaries, with
 * values by hand (issue 32: every decision threshold gets a test on both sides):
 * - innovation_gate: the 2-dof chi-square threshold -2 log(1 - p) of CSparseUpdateEngine and of
 *   CGateRecoveryUpdateEngine (a reading is used up to it, gated out beyond);
 * - recovery_count and recovery_min_updates of CGateRecoveryUpdateEngine;
 * - drop_static_after_unseen_steps and keep_last_poses of CDropPolicy.
 *
 * The scene: the ego at the origin with zero covariance, one landmark at (5, 0) with covariance
 * 0.03 I, a Cartesian reading with R = 0.01 I and innovation (nu, 0): S = 0.04 I, NIS = nu^2 /
 * 0.04. With p = 0.99 the gate is -2 log 0.01 = 9.2103: nu = 0.60 (NIS 9.0) passes, nu = 0.61
 * (NIS 9.3025) does not. */
#include <dynslam/estimator/drop_policy.h>
#include <dynslam/estimator/robust_update_engines.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace dynslam;
using namespace dynslam::estimator;

namespace
{
struct TOne
{
	Eigen::VectorXd x = Eigen::VectorXd::Zero(5);
	ekf::RowMatrixXd P = ekf::RowMatrixXd::Zero(5, 5);
	std::vector<TStaticObservation> obs;
	TUpdateContext ctx;
	explicit TOne(double nu, double gateProb = 0.99)
	{
		x << 0, 0, 0, 5, 0;
		P(3, 3) = P(4, 4) = 0.03;
		ctx.R = 0.01 * Eigen::Matrix2d::Identity();
		ctx.gate_threshold = gateThreshold2Dof(gateProb);
		obs.push_back({7, Eigen::Vector2d(5 + nu, 0), 3});
	}
};
}  // namespace

TEST(GateThresholds, ChiSquareThresholdOfTwoDof)
{
	EXPECT_NEAR(gateThreshold2Dof(0.99), 9.210340371976182, 1e-12);
	EXPECT_NEAR(gateThreshold2Dof(0.95), 5.991464547107979, 1e-12);
	EXPECT_TRUE(std::isinf(gateThreshold2Dof(0)));
}

TEST(GateThresholds, InnovationGateOfTheSparseUpdate)
{
	for (const double nu : {0.60, 0.61})
	{
		TOne s(nu);
		CSparseUpdateEngine e;
		const TUpdateResult r = e.update(s.x, s.P, s.obs, s.ctx);
		const bool used = nu == 0.60;
		EXPECT_EQ(r.updates, used ? 1u : 0u) << "nu " << nu << ", NIS " << nu * nu / 0.04;
		EXPECT_EQ(r.gated_out, used ? 0u : 1u) << nu;
		if (used)
		{
			EXPECT_NEAR(r.nis, 9.0, 1e-9);
		}
		// Used: gain 0.03 / 0.04 along x; gated out: the landmark is unchanged.
		EXPECT_NEAR(s.x[3], used ? 5 + 0.75 * nu : 5.0, 1e-12) << nu;
	}
}

TEST(GateThresholds, InnovationGateOfTheGateWithRecovery)
{
	for (const double nu : {0.60, 0.61})
	{
		TOne s(nu);
		CGateRecoveryUpdateEngine e({});
		const TUpdateResult r = e.update(s.x, s.P, s.obs, s.ctx);
		EXPECT_EQ(r.updates, nu == 0.60 ? 1u : 0u) << "nu " << nu;
		EXPECT_EQ(r.gated_out, nu == 0.60 ? 0u : 1u) << "nu " << nu;
	}
}

// count = 3, min_updates = 2: a landmark accepted twice, then rejected: the ego covariance is
// inflated at the third rejection in a row, not at the second. (The ego has zero covariance
// here, so the inflation changes no gating and the rejections go on: one inflation per step.)
TEST(GateThresholds, RecoveryAfterCountRejectionsOfAnEstablishedLandmark)
{
	TGateRecoveryParams p;
	p.count = 3;
	p.min_updates = 2;
	CGateRecoveryUpdateEngine e(p);
	const auto step = [&](double nu)
	{
		TOne s(nu);
		return e.update(s.x, s.P, s.obs, s.ctx);
	};
	EXPECT_EQ(step(0.1).updates, 1u);
	EXPECT_EQ(step(0.1).updates, 1u);
	EXPECT_EQ(step(1.0).gated_out, 1u);
	EXPECT_EQ(e.inflations(), 0u);
	EXPECT_EQ(step(1.0).gated_out, 1u);
	EXPECT_EQ(e.inflations(), 0u) << "inflated at the 2nd rejection in a row (count 3)";
	EXPECT_EQ(step(1.0).gated_out, 1u);
	EXPECT_EQ(e.inflations(), 1u) << "not inflated at the 3rd rejection in a row (count 3)";
	EXPECT_EQ(step(1.0).gated_out, 1u);
	EXPECT_EQ(e.inflations(), 2u);
	// An accepted reading resets the run of rejections.
	EXPECT_EQ(step(0.1).updates, 1u);
	step(1.0);
	step(1.0);
	EXPECT_EQ(e.inflations(), 2u);
	step(1.0);
	EXPECT_EQ(e.inflations(), 3u);
}

TEST(GateThresholds, RecoveryNeedsMinUpdatesAcceptedReadings)
{
	for (const int accepted : {1, 2})
	{
		TGateRecoveryParams p;
		p.count = 1;
		p.min_updates = 2;
		CGateRecoveryUpdateEngine e(p);
		for (int k = 0; k < accepted; ++k)
		{
			TOne s(0.1);
			e.update(s.x, s.P, s.obs, s.ctx);
		}
		TOne s(1.0);
		e.update(s.x, s.P, s.obs, s.ctx);
		EXPECT_EQ(e.inflations(), accepted >= 2 ? 1u : 0u) << accepted << " accepted readings";
	}
}

TEST(DropPolicyThresholds, StaticLandmarkUnseenForNSteps)
{
	TDropOptions o;
	o.drop_static_after_unseen_steps = 3;
	CDropPolicy d(o);
	d.noteSeen(4, 5);
	EXPECT_FALSE(d.staticDue(4, 7, 0));  // unseen for 2 steps
	EXPECT_TRUE(d.staticDue(4, 8, 0));   // for 3
	// Never noted: counted from the step it was added.
	EXPECT_FALSE(d.staticDue(9, 11, 9));
	EXPECT_TRUE(d.staticDue(9, 12, 9));
	o.drop_static_after_unseen_steps = 0;  // never
	EXPECT_FALSE(CDropPolicy(o).staticDue(4, 1000, 0));
}

TEST(DropPolicyThresholds, ObjectPosesBeyondTheLastK)
{
	TDropOptions o;
	o.keep_last_poses = 2;
	const CDropPolicy d(o);
	EXPECT_EQ(d.posesToDrop(1), 0u);
	EXPECT_EQ(d.posesToDrop(2), 0u);
	EXPECT_EQ(d.posesToDrop(3), 1u);
	EXPECT_EQ(d.posesToDrop(7), 5u);
	o.keep_last_poses = 0;  // taken as 1
	EXPECT_EQ(CDropPolicy(o).posesToDrop(1), 0u);
	EXPECT_EQ(CDropPolicy(o).posesToDrop(2), 1u);
}
