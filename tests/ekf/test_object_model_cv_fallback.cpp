/** object_model = cv: the fallback of a lost object (cv_fallback_steps). An object that turns
 * hard is gated out, falls back to the paper's formulation and is used again; a steady object
 * never falls back. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/core/models/object_pose.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/constant_velocity.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <sstream>

#include "object_model_setup.h"
#include "tiny_scenario.h"

using namespace dynslam;
using dynslam_test::TinyScenarioOptions;

namespace
{
TinyScenarioOptions scenario(unsigned seed)
{
	TinyScenarioOptions o;
	o.seed = seed;
	o.objects = 2;
	o.features_per_object = 3;
	o.landmarks = 3;
	o.cartesian_noise = true;
	o.steps = 40;
	o.object_turn_rate = 0.0;
	return o;
}

void configure(CDynamicKFSLAM2D& f, const TinyScenarioOptions& o)
{
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0.setZero();
	f.options.Sigma_xi = Eigen::Matrix2d::Identity() * 1e-6;
	f.options.object_model = "cv";
	f.options.cv.dt = 1.0;
	f.options.cv.accel_psd = Eigen::Vector3d(1e-9, 1e-9, 1e-11);
	f.options.cv.velocity_prior_std = Eigen::Vector3d(1e-4, 1e-4, 1e-5);
	f.reset();
}

Eigen::Matrix2Xd trueFeatures(const dynslam_test::TinyObject& ob, int k)
{
	Eigen::Matrix2Xd F(2, ob.off.cols());
	for (int i = 0; i < ob.off.cols(); ++i)
		F.col(i) = ob.c + ob.v * k + models::rot2(ob.w * k) * ob.off.col(i);
	return F;
}

std::vector<dynslam_test::TinyObject> trueObjects(const TinyScenarioOptions& o)
{
	std::mt19937 g(o.seed);
	std::uniform_real_distribution<double> U(-14, 14);
	for (int i = 0; i < 2 * o.landmarks; ++i) U(g);
	return dynslam_test::makeTinyObjects(o, g, U);
}

/** Object 0 turns left by 90 degrees at step kb (same speed, no rotation of its body). */
Eigen::Matrix2Xd turnedFeatures(const dynslam_test::TinyObject& ob, int kb, int k)
{
	Eigen::Matrix2Xd F = trueFeatures(ob, k);
	const Eigen::Vector2d shift = (models::rot2(M_PI / 2) - Eigen::Matrix2d::Identity()) * ob.v;
	F.colwise() += shift * double(k - kb);
	return F;
}

/** Object 0 stops dead at step kb (turn: turns by 90 degrees instead): its readings from then
 * on see its features where they are then (the Cartesian readings shifted by the true
 * displacement, noise kept). */
void brakeObject0(dynslam_test::TinyScenario& sc, const TinyScenarioOptions& o, int kb,
                  bool turn = false)
{
	const auto ob = trueObjects(o)[0];
	for (size_t k = size_t(kb); k < sc.frames.size(); ++k)
	{
		auto obs = sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		const Eigen::Matrix2Xd now = trueFeatures(ob, int(k));
		const Eigen::Matrix2Xd stop = turn ? turnedFeatures(ob, kb, int(k)) : trueFeatures(ob, kb);
		for (auto& m : obs->sensedData)
		{
			const int i = m.landmarkID - ids::objectFeatureId(0, 0);
			if (i < 0 || i >= ob.off.cols()) continue;
			Eigen::Vector2d z(m.range * std::cos(m.yaw), m.range * std::sin(m.yaw));
			z += models::cartesianObserve(sc.ego[k], stop.col(i)) -
			     models::cartesianObserve(sc.ego[k], now.col(i));
			const Eigen::Vector2d rb = models::cartesianToRangeBearing(z);
			m.range = float(rb[0]);
			m.yaw = float(rb[1]);
		}
	}
}
}  // namespace

// ------------------------------------------------------------------------------------------
// Fallback of a lost object (cv_fallback_steps, doc/state-layout.md "Fallback of a lost object")
// ------------------------------------------------------------------------------------------
namespace
{
struct TFallbackRun
{
	double object0 = -1, ego = 0;
	size_t readings = 0, accounted = 0;  ///< object readings in the rawlog / in the reports
	size_t lateUpdates = 0, lateGated = 0, fallbacks = 0, reinits = 0, cvFallbacks = 0;
};

/** Object 0 turns by 90 degrees at step kb; tight process noise, cv_gate = 0.999. */
TFallbackRun runTurn(const dynslam_test::TinyScenario& sc, const TinyScenarioOptions& o, int kb,
                     int fallbackSteps)
{
	CDynamicKFSLAM2D f;
	configure(f, o);
	f.options.cv_gate = 0.999;
	f.options.cv.fallback_steps = fallbackSteps;
	f.reset();
	TFallbackRun r;
	const size_t n = sc.actions.size();
	for (size_t k = 0; k < n; ++k)
	{
		f.processActionObservation(sc.actions[k], sc.frames[k]);
		const auto obs = sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		for (const auto& m : obs->sensedData) r.readings += ids::isObjectFeature(m.landmarkID);
		const TStepReport& s = f.getLastStepReport();
		// Every object reading is an update, gated out (counted), or a time-0 / time-t feature.
		r.accounted += s.object_feature_updates + s.object_gated_out + s.object_features_new +
		               s.object_features_t + s.skipped_unknown_object_feature;
		r.fallbacks += s.object_fallbacks;
		r.reinits += s.object_reinits;
		if (k + 5 >= n)
		{
			r.lateUpdates += s.object_feature_updates;
			r.lateGated += s.object_gated_out;
		}
	}
	const auto p = f.getEgoPose().mean;
	r.ego = std::hypot(p.x() - sc.ego.back()[0], p.y() - sc.ego.back()[1]);
	const auto ob = trueObjects(o)[0];
	for (const auto& [obj, tr] : f.getObjectTracks())
		if (obj == 0)
		{
			const int t0 = f.router().registry().at(obj).first_step;
			const Eigen::Vector3d xi =
			    models::objectPoseInverse(trueFeatures(ob, t0), turnedFeatures(ob, kb, int(n) - 1));
			r.object0 = (tr.poses.back().mean.head<2>() - xi.head<2>()).norm();
		}
	r.cvFallbacks =
	    dynamic_cast<const estimator::CConstantVelocity&>(f.objectMotionModel()).fallbackCount();
	return r;
}
}  // namespace

TEST(ObjectModelCvFallback, TurningObjectIsGatedOutThenUsedAgain)
{
	const TinyScenarioOptions o = scenario(7);
	auto sc = dynslam_test::makeTinyScenario(o);
	const int kb = 20;
	brakeObject0(sc, o, kb, true);
	const TFallbackRun off = runTurn(sc, o, kb, 0), on = runTurn(sc, o, kb, 3);
	std::printf(
	    "[ measured ] object 0 turns at step %d: object pose error off %.4f m, on %.4f m; ego "
	    "error off %.4f m, on %.4f m; last 5 steps: updates %zu / %zu, gated %zu / %zu; "
	    "fallbacks %zu, re-initialisations %zu\n",
	    kb, off.object0, on.object0, off.ego, on.ego, off.lateUpdates, on.lateUpdates,
	    off.lateGated, on.lateGated, on.fallbacks, on.reinits);
	// Off: object 0 is gated out for good and coasts on its old velocity.
	EXPECT_GT(off.lateGated, 0u);
	EXPECT_EQ(off.fallbacks, 0u);
	// On: lost once, re-initialised from two poses, then its readings are updates again.
	EXPECT_EQ(on.fallbacks, 1u);
	EXPECT_EQ(on.cvFallbacks, 1u);
	EXPECT_EQ(on.reinits, 1u);
	EXPECT_EQ(on.lateGated, 0u);
	EXPECT_EQ(on.lateUpdates, off.lateUpdates + off.lateGated);
	ASSERT_GE(on.object0, 0);
	EXPECT_LT(on.object0, 0.1 * off.object0);
	EXPECT_LT(on.ego, 2 * off.ego + 0.01);  // the turning object does not drag the ego
	// No reading is dropped silently.
	EXPECT_EQ(off.accounted, off.readings);
	EXPECT_EQ(on.accounted, on.readings);
}

TEST(ObjectModelCvFallback, SteadyObjectsNeverFallBack)
{
	const TinyScenarioOptions o = scenario(8);
	const auto sc = dynslam_test::makeTinyScenario(o);
	const TFallbackRun off = runTurn(sc, o, 0, 0), on = runTurn(sc, o, 0, 1);
	EXPECT_EQ(on.fallbacks, 0u);
	EXPECT_EQ(on.ego, off.ego);  // the same numbers to the last digit
}

TEST(ObjectModelCvFallback, CounterAndIniKey)
{
	estimator::TCvParams p;
	p.fallback_steps = 2;
	estimator::CConstantVelocity m(p);
	EXPECT_FALSE(m.reportGating(3, true));
	EXPECT_FALSE(m.reportGating(3, false));  // a used reading restarts the count
	EXPECT_FALSE(m.reportGating(3, true));
	EXPECT_FALSE(m.reportGating(4, true));  // per object
	EXPECT_TRUE(m.reportGating(3, true));   // two in a row: lost
	EXPECT_FALSE(m.reportGating(3, true));  // counted afresh after a fallback
	EXPECT_EQ(m.fallbackCount(), 1u);
	m.resetObjectState();
	EXPECT_EQ(m.fallbackCount(), 0u);
	EXPECT_FALSE(estimator::CConstantVelocity(estimator::TCvParams{}).reportGating(3, true));
	p.fallback_steps = -1;
	EXPECT_THROW(estimator::CConstantVelocity{p}, std::invalid_argument);
	mrpt::config::CConfigFileMemory ini;
	ini.setContent(
	    "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-4 1e-4]\n"
	    "object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_fallback_steps = 3\n");
	CDynamicKFSLAM2D f;
	f.loadOptions(ini);
	EXPECT_EQ(f.options.cv.fallback_steps, 3);
	std::ostringstream dump;
	f.options.dumpToTextStream(dump);
	EXPECT_NE(dump.str().find("cv_fallback_steps              = 3"), std::string::npos);
	ini.setContent(
	    "[DynamicKFSLAM]\nmeasurement_model = cartesian\nSigma_v = [1e-4 1e-4]\n"
	    "object_model = cv\n[ObjectModel]\ncv_dt = 0.5\ncv_fallback_steps = -2\n");
	EXPECT_THROW(f.loadOptions(ini), std::invalid_argument);
}
