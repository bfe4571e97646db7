/** object_model = cv (issue 13): objects that tell the ego only once converged
 * (cv_ego_velocity_std, doc/state-layout.md "Objects that tell the ego only once converged").
 * While an object's velocity std is above the key, its readings correct only the object (a
 * Schmidt update): the ego and the static map then evolve exactly as in the paper's filter,
 * where object readings never update them. Off (0), the filter is today's to the last digit. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/ground_truth.h>
#include <dynslam/sim/scenario.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <sstream>

#include "highway_cv_setup.h"
#include "object_model_setup.h"

using namespace dynslam;

namespace
{
void configure(CDynamicKFSLAM2D& f, const sim::TScenarioOptions& o, const std::string& model,
               double egoStd)
{
	dynslam_test::configureHighwayCv(f, o, model, Eigen::Vector3d(1e-6, 1e-6, 1e-8));
	f.options.cv.ego_velocity_std = egoStd;
	f.reset();
}

/** The ego's mean and covariance (the first 3 entries in every layout). */
Eigen::VectorXd ego(const CDynamicKFSLAM2D& f)
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	f.getStateWithoutPads(x, P);
	Eigen::VectorXd out(12);
	out << x.head<3>(), P.topLeftCorner(3, 3).reshaped();
	return out;
}
}  // namespace

TEST(ObjectModelCvEgoDelay, UnconvergedObjectsLeaveTheEgoAsInThePaperFilter)
{
	// One seeded w3v1 highway run through: the paper's filter; cv with the key so small that no
	// object ever converges (every object update a Schmidt update); cv off (0) and cv with a key
	// no velocity std reaches (1e9: never a Schmidt update); cv with 0.05 m/s (some of each).
	sim::TScenarioOptions o = dynslam_test::highwayW3v1();
	const TGroundTruth gt = sim::buildGroundTruth(o);
	const sim::TSimulatedRun run = sim::simulateMeasurements(gt, o, 9001);
	CDynamicKFSLAM2D paper, never, off, always, mid;
	configure(paper, o, "paper", 0);
	configure(never, o, "cv", 1e-12);
	configure(off, o, "cv", 0);
	configure(always, o, "cv", 1e9);
	configure(mid, o, "cv", 0.05);
	double worstNever = 0, worstOff = 0, worstMid = 0;
	size_t updates = 0;
	for (size_t k = 0; k < 40; ++k)
	{
		for (CDynamicKFSLAM2D* f : {&paper, &never, &off, &always, &mid})
			f->processActionObservation(run.actions[k], run.frames[k]);
		updates += never.getLastStepReport().object_feature_updates;
		ASSERT_EQ(dynslam_test::meanAndCovariance(off), dynslam_test::meanAndCovariance(always))
		    << "step " << k;
		const Eigen::VectorXd p = ego(paper);
		worstNever = std::max(worstNever, (ego(never) - p).cwiseAbs().maxCoeff());
		worstOff = std::max(worstOff, (ego(off) - p).cwiseAbs().maxCoeff());
		worstMid = std::max(worstMid, (ego(mid) - ego(off)).cwiseAbs().maxCoeff());
	}
	std::printf(
	    "[ measured ] %zu object updates; largest ego difference to the paper's filter: "
	    "Schmidt always %.3g, off %.3g; 0.05 m/s vs off %.3g\n",
	    updates, worstNever, worstOff, worstMid);
	ASSERT_GT(updates, 100u);
	EXPECT_LT(worstNever, 1e-12);  // the objects never touch the ego
	EXPECT_GT(worstOff, 1e-6);     // the test is not vacuous: used, they move it
	EXPECT_GT(worstMid, 1e-9);     // the early Schmidt updates change the ego's path
}

TEST(ObjectModelCvEgoDelay, OptionsDumpAndBadInput)
{
	dynslam_test::expectScalarCvKey(&estimator::TCvParams::ego_velocity_std, "cv_ego_velocity_std",
	                                0.02, "0.02");
}
