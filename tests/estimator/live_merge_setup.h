#pragma once
// Shared by the live-merge tests (test_live_merge.cpp, test_live_merge_rate.cpp).
#include <dynslam/sim/scenario.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <map>
#include <vector>

namespace dynslam_test
{
/** Removes the readings of true object `obj`, features >= 2, before step `until` (they are
 * first seen then: a car split into two objects). */
inline void delayHalfOfObject(dynslam::sim::TSimulatedRun& sim, int32_t obj, int until)
{
	std::vector<dynslam::io::TReadingClass> kept;
	std::map<int, int> shift;  // step -> readings removed so far in it
	for (const dynslam::io::TReadingClass& c : sim.classes)
	{
		dynslam::io::TReadingClass d = c;
		d.index -= shift[c.step];
		if (c.object == obj && c.feature >= 2 && c.step < until)
		{
			auto o = sim.frames.at(size_t(c.step))
			             ->getObservationByClass<mrpt::obs::CObservationBearingRange>();
			o->sensedData.erase(o->sensedData.begin() + d.index);
			++shift[c.step];
			continue;
		}
		kept.push_back(d);
	}
	sim.classes = kept;
}
}  // namespace dynslam_test
