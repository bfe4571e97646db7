/** object_model = cv (issue 13 item 3): per-object process-noise inflation. An object that
 * brakes hard is tracked again when its innovations trigger the inflation; a steady object never
 * triggers it, and the filter's results are then those of the rule switched off. */
#include <dynslam/CDynamicKFSLAM2D.h>
#include <dynslam/estimator/constant_velocity.h>
#include <dynslam/models/object_pose.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

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

void configure(CDynamicKFSLAM2D& f, const TinyScenarioOptions& o, bool inflation)
{
	f.options.measurement_model = models::MeasurementModel::Cartesian;
	f.options.Sigma_v = o.Sigma_v;
	f.options.Sigma_0.setZero();
	f.options.Sigma_xi = Eigen::Matrix2d::Identity() * 1e-6;
	f.options.object_model = "cv";
	f.options.cv.dt = 1.0;
	f.options.cv.accel_psd = Eigen::Vector3d(1e-9, 1e-9, 1e-11);
	f.options.cv.velocity_prior_std = Eigen::Vector3d(1e-4, 1e-4, 1e-5);
	f.options.cv.inflation_threshold = inflation ? 8.0 : 0.0;
	f.options.cv.inflation_factor = inflation ? 1e7 : 1.0;
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

/** Object 0 stops dead at step kb: its readings from then on see its features where they were
 * at kb (the Cartesian readings shifted by the true displacement, noise kept). */
void brakeObject0(dynslam_test::TinyScenario& sc, const TinyScenarioOptions& o, int kb)
{
	const auto ob = trueObjects(o)[0];
	for (size_t k = size_t(kb); k < sc.frames.size(); ++k)
	{
		auto obs = sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		const Eigen::Matrix2Xd now = trueFeatures(ob, int(k)), stop = trueFeatures(ob, kb);
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

struct TRun
{
	double ego = 0, object0 = -1;
	size_t inflations = 0;
	Eigen::VectorXd x;
};

TRun run(const dynslam_test::TinyScenario& sc, const TinyScenarioOptions& o, bool inflation, int kb)
{
	CDynamicKFSLAM2D f;
	configure(f, o, inflation);
	for (size_t k = 0; k < sc.actions.size(); ++k)
		f.processActionObservation(sc.actions[k], sc.frames[k]);
	TRun r;
	const auto p = f.getEgoPose().mean;
	r.ego = std::hypot(p.x() - sc.ego.back()[0], p.y() - sc.ego.back()[1]);
	const auto ob = trueObjects(o)[0];
	const int last = int(sc.actions.size()) - 1;
	for (const auto& [obj, tr] : f.getObjectTracks())
	{
		if (obj != 0) continue;
		const int t0 = f.router().registry().at(obj).first_step;
		const Eigen::Vector3d xi = models::objectPoseInverse(
		    trueFeatures(ob, t0), trueFeatures(ob, kb >= 0 ? std::min(kb, last) : last));
		r.object0 = (tr.poses.back().mean.head<2>() - xi.head<2>()).norm();
	}
	const auto* cv = dynamic_cast<const estimator::CConstantVelocity*>(&f.objectMotionModel());
	r.inflations = cv ? cv->inflationCount() : 0;
	r.x = f.fullMean().asEigen();
	return r;
}
}  // namespace

TEST(ObjectModelCvInflation, BrakingObjectIsTrackedAgain)
{
	const TinyScenarioOptions o = scenario(7);
	auto sc = dynslam_test::makeTinyScenario(o);
	const int kb = 20;
	brakeObject0(sc, o, kb);
	const TRun off = run(sc, o, false, kb), on = run(sc, o, true, kb);
	std::printf(
	    "[ measured ] object 0 brakes at step %d: object pose error off %.4f m, on %.4f m; ego "
	    "error off %.4f m, on %.4f m; %zu inflations\n",
	    kb, off.object0, on.object0, off.ego, on.ego, on.inflations);
	ASSERT_GE(off.object0, 0);
	ASSERT_GE(on.object0, 0);
	EXPECT_GT(on.inflations, 0u);
	EXPECT_LT(on.object0, 0.5 * off.object0);
	EXPECT_LT(on.ego, 0.5 * off.ego);
}

TEST(ObjectModelCvInflation, SteadyObjectsNeverTriggerIt)
{
	for (const unsigned seed : {7u, 8u, 9u})
	{
		const TinyScenarioOptions o = scenario(seed);
		const auto sc = dynslam_test::makeTinyScenario(o);
		const TRun off = run(sc, o, false, -1), on = run(sc, o, true, -1);
		std::printf("[ measured ] seed %u, steady objects: %zu inflations, ego error %.6f m\n",
		            seed, on.inflations, on.ego);
		EXPECT_EQ(on.inflations, 0u);
		ASSERT_EQ(on.x.size(), off.x.size());
		EXPECT_EQ(on.x, off.x);  // the rule is off in effect: the same numbers to the last digit
	}
}

TEST(ObjectModelCvInflation, RuleResetsWhenConsistent)
{
	estimator::TCvParams p;
	p.inflation_threshold = 4.0;
	p.inflation_factor = 100.0;
	estimator::CConstantVelocity m(p);
	EXPECT_TRUE(m.tracksInnovations());
	EXPECT_EQ(m.processNoiseScale(3), 1.0);
	m.reportInnovations(3, 6 * 5.0, 6);  // mean NIS/dof 5 > 4: inflate the next prediction
	EXPECT_EQ(m.processNoiseScale(3), 100.0);
	EXPECT_EQ(m.processNoiseScale(4), 1.0);  // per object
	m.reportInnovations(3, 6 * 1.0, 6);      // consistent again: back to 1
	EXPECT_EQ(m.processNoiseScale(3), 1.0);
	EXPECT_EQ(m.inflationCount(), 1u);
	m.reportInnovations(3, 6 * 5.0, 6);
	m.resetObjectState();
	EXPECT_EQ(m.processNoiseScale(3), 1.0);
	EXPECT_EQ(m.inflationCount(), 0u);
	estimator::TCvParams off;  // the defaults: off
	EXPECT_FALSE(estimator::CConstantVelocity(off).tracksInnovations());
	p.inflation_factor = 0.5;
	EXPECT_THROW(estimator::CConstantVelocity{p}, std::invalid_argument);
	p.inflation_factor = 2;
	p.inflation_threshold = -1;
	EXPECT_THROW(estimator::CConstantVelocity{p}, std::invalid_argument);
}

TEST(ObjectModelCvInflation, WindowAndDecay)
{
	// The window averages the NIS over the object's last steps with readings; the decay brings
	// the factor back to 1 geometrically (doc/state-layout.md "Process-noise inflation").
	estimator::TCvParams p;
	p.inflation_threshold = 4.0;
	p.inflation_factor = 100.0;
	p.inflation_window = 3;
	p.inflation_decay = 0.1;
	estimator::CConstantVelocity m(p);
	m.reportInnovations(3, 2 * 1.0, 2);  // window {1}: mean 1
	EXPECT_EQ(m.processNoiseScale(3), 1.0);
	m.reportInnovations(3, 2 * 9.0, 2);  // window {1, 9}: mean 5 > 4
	EXPECT_EQ(m.processNoiseScale(3), 100.0);
	m.reportInnovations(3, 2 * 1.0, 2);  // window {1, 9, 1}: mean 11/3 <= 4: decays
	EXPECT_DOUBLE_EQ(m.processNoiseScale(3), 10.0);
	m.reportInnovations(3, 6 * 1.0, 6);  // window {9, 1, 1 (6 dof)}: 26 / 10 dof: decays to 1
	EXPECT_EQ(m.processNoiseScale(3), 1.0);
	m.reportInnovations(3, 2 * 4.5, 2);  // window {1, 1 (6 dof), 4.5}: 17 / 10 dof: stays 1
	EXPECT_EQ(m.processNoiseScale(3), 1.0);
	EXPECT_EQ(m.inflationCount(), 1u);
	// The one-step rule (window 1, decay 0) inflates on that last step.
	p.inflation_window = 1;
	p.inflation_decay = 0;
	estimator::CConstantVelocity one(p);
	one.reportInnovations(3, 2 * 4.5, 2);
	EXPECT_EQ(one.processNoiseScale(3), 100.0);
	p.inflation_window = 0;
	EXPECT_THROW(estimator::CConstantVelocity{p}, std::invalid_argument);
	p.inflation_window = 2;
	p.inflation_decay = 1.0;
	EXPECT_THROW(estimator::CConstantVelocity{p}, std::invalid_argument);
}

TEST(ObjectModelCvInflation, IniKeys)
{
	const auto load = [](const std::string& extra)
	{
		mrpt::config::CConfigFileMemory ini;
		ini.setContent(std::string("[DynamicKFSLAM]\nmeasurement_model = cartesian\n"
		                           "Sigma_v = [1e-4 1e-4]\nobject_model = cv\ncv_dt = 0.5\n") +
		               extra);
		CDynamicKFSLAM2D f;
		f.loadOptions(ini);
		return f.objectMotionModel().tracksInnovations();
	};
	EXPECT_FALSE(load(""));  // off by default
	EXPECT_TRUE(load("cv_inflation_threshold = 8\ncv_inflation_factor = 100\n"));
	EXPECT_FALSE(load("cv_inflation_threshold = 8\n"));  // factor 1: off
	EXPECT_THROW(load("cv_inflation_factor = 0.5\n"), std::invalid_argument);
	EXPECT_THROW(load("cv_inflation_threshold = -1\n"), std::exception);
	EXPECT_TRUE(
	    load("cv_inflation_threshold = 8\ncv_inflation_factor = 100\n"
	         "cv_inflation_window = 3\ncv_inflation_decay = 0.5\n"));
	EXPECT_THROW(load("cv_inflation_window = 0\n"), std::invalid_argument);
	EXPECT_THROW(load("cv_inflation_decay = 1\n"), std::invalid_argument);
}
