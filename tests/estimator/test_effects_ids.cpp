/** What the ID-labelled dynamic filter (feature_labels = ids, CIdRangeRouter) does with the
 * rawlogs of issue 12's simulator effects: each case is a clear outcome, never a crash. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/sim/scenario.h>
#include <dynslam_test/highway_filter_setup.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <set>
#include <sstream>

using namespace dynslam;

namespace
{
const std::string kIni = dynslam_test::highwayFilterIni();

sim::TScenarioOptions scenario(const std::string& cfg)
{
	return dynslam_test::shippedScenario(cfg);
}

struct TRun
{
	sim::TSimulatedRun sim;
	TStepReport total;
	size_t steps = 0, objects = 0, statics = 0;
};

TRun runFilter(const sim::TScenarioOptions& o)
{
	TRun r;
	r.sim = sim::simulateMeasurements(sim::buildGroundTruth(o), o, o.noise_seed);
	mrpt::config::CConfigFileMemory ini(kIni);
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(ini, "DynamicKFSLAM");
	ekf.reset();
	for (size_t k = 0; k < r.sim.actions.size(); ++k)
	{
		ekf.processActionObservation(r.sim.actions[k], r.sim.frames[k]);
		const TStepReport& s = ekf.getLastStepReport();
		r.total.static_new += s.static_new;
		r.total.skipped_unknown_object_feature += s.skipped_unknown_object_feature;
		++r.steps;
	}
	r.objects = ekf.getObjectTracks().size();
	r.statics = allStaticLandmarks(ekf).size();
	return r;
}

sim::TScenarioOptions highwayWith(const std::string& key, const std::string& value)
{
	std::ostringstream ini;
	scenario("highway.ini").dumpToTextStream(ini);
	return sim::loadScenarioFromText(ini.str() + "\n[Effects]\n" + key + " = " + value + "\n");
}
}  // namespace

TEST(EffectsWithIds, UnknownClutterIdIsAssociatedOrStartsALandmark)
{
	// Issue 30: a clutter reading with MRPT's unknown landmark ID -1 no longer stops the filter
	// (it threw "... (landmark ID -1) is in no known ID range"); it is associated with a static
	// landmark or starts one, as CRangeBearingKFSLAM2D does, and every -1 reading is counted.
	sim::TScenarioOptions o = highwayWith("clutter_ids", "unknown");
	o.effects.clutter_per_step = 1;
	const auto run = sim::simulateMeasurements(sim::buildGroundTruth(o), o, o.noise_seed);
	mrpt::config::CConfigFileMemory ini(kIni);
	CDynamicKFSLAM2D ekf;
	ekf.loadOptions(ini, "DynamicKFSLAM");
	ekf.reset();
	size_t unknown = 0, counted = 0;
	for (size_t k = 0; k < 20 && k < run.actions.size(); ++k)
	{
		ASSERT_NO_THROW(ekf.processActionObservation(run.actions[k], run.frames[k])) << k;
		for (const auto& m : run.frames[k]
		                         ->getObservationByClass<mrpt::obs::CObservationBearingRange>()
		                         ->sensedData)
			unknown += m.landmarkID == -1;
		const TStepReport& rep = ekf.getLastStepReport();
		counted += rep.unknown_id_associated + rep.unknown_id_new + rep.skipped_unknown_id;
	}
	EXPECT_GT(unknown, 0u);
	EXPECT_EQ(counted, unknown);
}

TEST(EffectsWithIds, AnonymousIdsAreAllTakenForStaticLandmarks)
{
	sim::TScenarioOptions o = highwayWith("anonymous_ids", "true");
	const TRun r = runFilter(o);
	std::set<int32_t> ids;
	for (const auto& c : r.sim.classes) ids.insert(c.id);
	EXPECT_EQ(r.objects, 0u) << "no ID range tells a moving feature: no object is created";
	EXPECT_EQ(r.total.static_new, ids.size()) << "every anonymous track becomes a landmark";
}

TEST(EffectsWithIds, BrokenObjectTracksAreCountedSkips)
{
	const sim::TScenarioOptions o = highwayWith("track_break_gap", "4");
	const TRun r = runFilter(o);
	size_t brokenObjectReadings = 0, brokenStatic = 0;
	std::set<int32_t> staticIds;
	for (const auto& c : r.sim.classes)
	{
		if (c.object >= 0 && c.id != c.true_id) ++brokenObjectReadings;
		if (ids::isStatic(c.id)) staticIds.insert(c.id);
		if (c.object < 0 && c.id != c.true_id) ++brokenStatic;
	}
	EXPECT_GT(brokenObjectReadings, 0u);
	// A new feature index of a known object, not seen at the object's time 0: skipped, counted.
	EXPECT_EQ(r.total.skipped_unknown_object_feature, brokenObjectReadings);
	// A broken static track is a new static landmark.
	EXPECT_EQ(r.total.static_new, staticIds.size());
}

TEST(EffectsWithIds, ClutterWithFreshIdsAndMissedDetectionsRun)
{
	const TRun r = runFilter(scenario("highway_clutter.ini"));
	std::set<int32_t> staticIds;
	size_t clutter = 0;
	for (const auto& c : r.sim.classes)
	{
		if (ids::isStatic(c.id)) staticIds.insert(c.id);
		clutter += c.cls == io::TrueClass::Clutter;
	}
	EXPECT_EQ(clutter, 2 * r.steps);
	EXPECT_EQ(r.total.static_new, staticIds.size()) << "each clutter reading: a new landmark";
	EXPECT_EQ(r.objects, 3u);
}
