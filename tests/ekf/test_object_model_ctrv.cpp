/** object_model = ctrv (issue 13): the constant turn rate and velocity object model in the
 * dynamic EKF (estimator::CConstantTurnRate: CV's machinery with models::ctrvPredict). Objects
 * on arcs are tracked better than with cv, and the ego gains; a one-feature object (no turn
 * rate) is the cv filter exactly; options and bad input. */
#include <dynslam/core/models/object_pose.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "object_model_setup.h"
#include "tiny_scenario.h"

using namespace dynslam;
using dynslam_test::TinyScenarioOptions;

namespace
{
TinyScenarioOptions arcScenario(unsigned seed, int landmarks)
{
	TinyScenarioOptions o;
	o.seed = seed;
	o.objects = 2;
	o.features_per_object = 3;
	o.landmarks = landmarks;
	o.cartesian_noise = true;
	o.steps = 40;
	o.object_turn_rate = 0.04;  // objects 0 and 1 turn by 0.04 and 0.08 rad per step
	o.objects_on_arcs = true;
	return o;
}

/** The centre of object ob at step k (on its circle). */
Eigen::Vector2d centreAt(const dynslam_test::TinyObject& ob, int k)
{
	const double a = ob.w * k;
	return ob.c + (Eigen::Matrix2d() << std::sin(a), std::cos(a) - 1, 1 - std::cos(a), std::sin(a))
	                      .finished() *
	                  ob.v / ob.w;
}

/** The true pose map xi (models/object_pose.h) of object ob at step k, relative to its first
 * sighting k0: rotation a = w (k - k0) about the time-k0 centroid c0, then the translation
 * d = c(k) + R(a) (c0 - c(k0)) - c0 that puts the centre at its place on the circle. */
Eigen::Vector3d trueXi(const dynslam_test::TinyObject& ob, int k0, int k)
{
	const double a = ob.w * (k - k0);
	const Eigen::Vector2d c0 = centreAt(ob, k0) + models::rot2(ob.w * k0) * ob.off.rowwise().mean();
	const Eigen::Vector2d d = centreAt(ob, k) + models::rot2(a) * (c0 - centreAt(ob, k0)) - c0;
	return {d[0], d[1], a};
}

struct TErrors
{
	double ego = 0, object = 0;
};

TErrors runOnce(const TinyScenarioOptions& o, const std::string& model)
{
	const auto sc = dynslam_test::makeTinyScenario(o);
	std::mt19937 g(o.seed);  // the objects of makeTinyScenario(o) (same draws)
	std::uniform_real_distribution<double> U(-14, 14);
	for (int i = 0; i < 2 * o.landmarks; ++i) U(g);
	const auto objs = dynslam_test::makeTinyObjects(o, g, U);
	CDynamicKFSLAM2D f;
	dynslam_test::configureObjectModel(f, o, model);
	for (size_t k = 0; k < sc.actions.size(); ++k)
		f.processActionObservation(sc.actions[k], sc.frames[k]);
	TErrors e;
	const auto p = f.getEgoPose().mean;
	e.ego = std::hypot(p.x() - sc.ego.back()[0], p.y() - sc.ego.back()[1]);
	const auto tracks = f.getObjectTracks();
	for (const auto& [obj, tr] : tracks)
	{
		const auto& last = tr.poses.back();
		const Eigen::Vector3d xi = trueXi(objs[size_t(obj)], tr.first_step, last.step);
		e.object += (last.mean.head<2>() - xi.head<2>()).norm() / double(tracks.size());
	}
	return e;
}
}  // namespace

TEST(ObjectModelCtrv, ObjectsOnArcsAreTrackedBetterThanWithCv)
{
	// Two objects whose centres move on circles (CTRV truth), no static landmark: cv's
	// straight-line prediction lags the turn; ctrv's is the truth's motion.
	TErrors cv, ctrv;
	const int runs = 20;
	for (int r = 0; r < runs; ++r)
	{
		const TinyScenarioOptions o = arcScenario(200 + unsigned(r), 0);
		const TErrors a = runOnce(o, "cv"), b = runOnce(o, "ctrv");
		cv.ego += a.ego / runs;
		cv.object += a.object / runs;
		ctrv.ego += b.ego / runs;
		ctrv.object += b.object / runs;
	}
	std::printf(
	    "[ measured ] objects on arcs, mean of %d runs: final object position error cv %.4f m, "
	    "ctrv %.4f m; final ego position error cv %.4f m, ctrv %.4f m\n",
	    runs, cv.object, ctrv.object, cv.ego, ctrv.ego);
	// Measured: object 0.3592 m (cv) vs 0.0827 m (ctrv); ego 0.0845 vs 0.0851 m. Without
	// static landmarks the objects cannot fix the ego's linear drift (unknown velocities,
	// doc/results/results.md): the better object model does not move the ego, and must not hurt it.
	EXPECT_LT(ctrv.object, 0.5 * cv.object);
	EXPECT_LT(ctrv.ego, 1.05 * cv.ego);
}

TEST(ObjectModelCtrv, OneFeatureObjectIsTheCvFilter)
{
	// A one-feature object has a translation-only pose and no turn rate: ctrv is cv (the
	// documented fallback), to the last bit.
	TinyScenarioOptions o = arcScenario(5, 4);
	o.features_per_object = 1;
	const auto sc = dynslam_test::makeTinyScenario(o);
	CDynamicKFSLAM2D a, b;
	dynslam_test::configureObjectModel(a, o, "cv");
	dynslam_test::configureObjectModel(b, o, "ctrv");
	for (size_t k = 0; k < sc.actions.size(); ++k)
	{
		a.processActionObservation(sc.actions[k], sc.frames[k]);
		b.processActionObservation(sc.actions[k], sc.frames[k]);
	}
	EXPECT_GT(a.getLastStepReport().object_feature_updates, 0u);
	EXPECT_EQ(a.fullMean().asEigen(), b.fullMean().asEigen());
	EXPECT_EQ(a.fullCov().asEigen(), b.fullCov().asEigen());
}

TEST(ObjectModelCtrv, OptionsAndBadInput)
{
	const auto load = [](const std::string& extra)
	{ return dynslam_test::loadCartesianFilter(extra)->objectMotionModel().name(); };
	EXPECT_EQ(load("object_model = ctrv\n[ObjectModel]\ncv_dt = 0.5\n"), "ctrv");
	EXPECT_THROW(load("object_model = ctrv\n"), std::exception);  // cv_dt is required
	EXPECT_THROW(load("object_model = ctrv\n[ObjectModel]\ncv_dt = 0.5\n[DynamicKFSLAM]\nsmoothing "
	                  "= true\nkeep_last_poses = 3\n"),
	             std::invalid_argument);
	for (const char* bad : {"[0.5 0.5 0]", "[0.5 -1 0.1]"})
	{
		try
		{
			load(std::string(
			         "object_model = ctrv\n[ObjectModel]\ncv_dt = 0.5\ncv_velocity_prior_std = ") +
			     bad + "\n");
			ADD_FAILURE() << "no error for a prior std " << bad;
		}
		catch (const std::invalid_argument& e)
		{
			EXPECT_NE(std::string(e.what()).find("cv_velocity_prior_std"), std::string::npos)
			    << e.what();
		}
	}
}
