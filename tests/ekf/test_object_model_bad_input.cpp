/** object_model = cv / ctrv, the bad input (issue 13): an object seen once (documented:
 * it keeps its f_0, gets no velocity and updates nothing; the other objects are unaffected) and
 * a CTRV object with zero speed (nothing divides by the speed: it is tracked standing still).
 * Velocity priors that are not positive definite: ObjectModelCv.OptionsAndBadInput and
 * ObjectModelCtrv.OptionsAndBadInput. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>

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
	o.landmarks = 6;
	o.cartesian_noise = true;
	o.steps = 30;
	return o;
}

/** Removes every reading of object `obj` except those of step `keep`. */
void seeObjectOnlyAt(dynslam_test::TinyScenario& sc, int obj, size_t keep)
{
	for (size_t k = 0; k < sc.frames.size(); ++k)
	{
		if (k == keep) continue;
		auto& d =
		    sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>()->sensedData;
		d.erase(std::remove_if(d.begin(), d.end(),
		                       [&](const auto& m)
		                       {
			                       return m.landmarkID >= ids::objectFeatureId(obj, 0) &&
			                              m.landmarkID < ids::objectFeatureId(obj + 1, 0);
		                       }),
		        d.end());
	}
}

/** Object 0 stands still (its features where they are at step 0, readings from the true
 * ego with the scenario's noise re-drawn): zero speed, zero turn rate. */
void freezeObject0(dynslam_test::TinyScenario& sc, const TinyScenarioOptions& o)
{
	std::mt19937 g(o.seed + 100);
	std::map<int32_t, Eigen::Vector2d> at0;
	const auto& obs0 = sc.frames[0]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
	for (const auto& m : obs0->sensedData)
		if (m.landmarkID >= ids::objectFeatureId(0, 0) && m.landmarkID < ids::objectFeatureId(1, 0))
			at0[m.landmarkID] = models::cartesianInverse(
			    sc.ego[0], Eigen::Vector2d(m.range * std::cos(m.yaw), m.range * std::sin(m.yaw)));
	ASSERT_EQ(at0.size(), 3u) << "object 0 must be seen at step 0";
	for (size_t k = 0; k < sc.frames.size(); ++k)
	{
		auto obs = sc.frames[k]->getObservationByClass<mrpt::obs::CObservationBearingRange>();
		for (auto& m : obs->sensedData)
		{
			const auto it = at0.find(m.landmarkID);
			if (it == at0.end()) continue;
			Eigen::Vector2d z = models::cartesianObserve(sc.ego[k], it->second);
			if (k > 0) z += dynslam_test::gaussian(g, o.Sigma_v);
			const Eigen::Vector2d rb = models::cartesianToRangeBearing(z);
			m.range = float(rb[0]);
			m.yaw = float(rb[1]);
		}
	}
}

bool hasVelocity(const CDynamicKFSLAM2D& f, int32_t obj)
{
	for (const auto& b : f.getLayout().blocks())
		if (b.kind == estimator::BlockKind::ObjectVelocity && b.object == obj) return true;
	return false;
}
}  // namespace

TEST(ObjectModelBadInput, ObjectSeenOnceKeepsNoVelocityAndChangesNothingElse)
{
	for (const std::string model : {"cv", "ctrv"})
	{
		const TinyScenarioOptions o = scenario(5);
		auto once = dynslam_test::makeTinyScenario(o);
		seeObjectOnlyAt(once, 0, 3);
		auto none = dynslam_test::makeTinyScenario(o);
		seeObjectOnlyAt(none, 0, SIZE_MAX);  // object 0 never seen
		CDynamicKFSLAM2D a, b;
		dynslam_test::configureObjectModel(a, o, model);
		dynslam_test::configureObjectModel(b, o, model);
		for (size_t k = 0; k < once.actions.size(); ++k)
		{
			ASSERT_NO_THROW(a.processActionObservation(once.actions[k], once.frames[k]));
			b.processActionObservation(none.actions[k], none.frames[k]);
		}
		EXPECT_TRUE(a.fullMean().asEigen().allFinite());
		EXPECT_FALSE(hasVelocity(a, 0)) << model;  // seen once: no velocity
		EXPECT_TRUE(hasVelocity(a, 1)) << model;
		EXPECT_TRUE(a.getObjectTracks().count(0)) << model;  // but known, with its first pose
		// It updated nothing: the ego estimate is the one of the run without object 0.
		const Eigen::Vector3d ea = a.fullMean().asEigen().head<3>(),
		                      eb = b.fullMean().asEigen().head<3>();
		EXPECT_LT((ea - eb).norm(), 1e-12) << model;
	}
}

TEST(ObjectModelBadInput, CtrvObjectWithZeroSpeedStaysPut)
{
	const TinyScenarioOptions o = scenario(6);
	auto sc = dynslam_test::makeTinyScenario(o);
	freezeObject0(sc, o);
	CDynamicKFSLAM2D f;
	dynslam_test::configureObjectModel(f, o, "ctrv");
	for (size_t k = 0; k < sc.actions.size(); ++k)
		ASSERT_NO_THROW(f.processActionObservation(sc.actions[k], sc.frames[k]));
	const Eigen::VectorXd x = f.fullMean().asEigen();
	EXPECT_TRUE(x.allFinite());
	ASSERT_TRUE(hasVelocity(f, 0));
	const auto tracks = f.getObjectTracks();
	ASSERT_TRUE(tracks.count(0));
	const auto& last = tracks.at(0).poses.back();
	EXPECT_EQ(last.step, int(sc.actions.size()) - 1);
	// The pose map of a standing object is the identity: translation and rotation near 0.
	std::printf("[ measured ] ctrv, object 0 at rest: final pose map (%.2e, %.2e, %.2e)\n",
	            last.mean[0], last.mean[1], last.mean[2]);
	EXPECT_LT(last.mean.head<2>().norm(), 0.15);
	EXPECT_LT(std::abs(last.mean[2]), 0.01);
	const estimator::CPaddedLayout& L = f.getLayout();
	for (size_t b = 0; b < L.size(); ++b)
		if (L[b].kind == estimator::BlockKind::ObjectVelocity && L[b].object == 0)
		{
			const Eigen::VectorXd v = x(L.indices(b));
			std::printf("[ measured ] ctrv, object 0 at rest: velocity (%.2e, %.2e, %.2e)\n", v[0],
			            v[1], v[2]);
			EXPECT_LT(v.head<2>().norm(), 0.03);
			EXPECT_LT(std::abs(v[2]), 0.01);
		}
}
