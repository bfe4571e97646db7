/** Memory in an endless run: with record_dropped = false the filter keeps nothing that grows
 * with the number of steps, so the memory allocated by the process (heap in use plus mmapped
 * blocks) must stay flat once the state has reached its working size; with the default
 * record_dropped = true it grows by exactly the kept records. Same straight-track world as
 * Soak.* (bench/synthetic_world.h). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "alloc_stats.h"
#include "straight_track.h"

using namespace dynslam;

namespace
{
using dynslam_test::allocatedBytes;

struct TMemoryRun
{
	long growthBytes = 0;  ///< allocated at the end minus at step `from`
	size_t droppedPoses = 0, droppedStatic = 0;
};

TMemoryRun runStraight(bool recordDropped, int steps, int from)
{
	const dynslam_bench::TSyntheticOptions o = dynslam_test::straightTrack(11);
	dynslam_bench::CSyntheticWorld world(o);
	CDynamicKFSLAM2D f;
	dynslam_test::configureForStraightTrack(f, o);
	f.options.keep_last_poses = 1;
	f.options.record_dropped = recordDropped;
	f.reset();
	TMemoryRun r;
	long atFrom = 0;
	for (int k = 0; k < steps; ++k)
	{
		mrpt::obs::CActionCollection::Ptr a;
		mrpt::obs::CSensoryFrame::Ptr sf;
		world.next(a, sf);  // the world's own per-step objects are freed with a and sf
		f.processActionObservation(a, sf);
		r.droppedPoses += f.getLastStepReport().dropped_poses;
		r.droppedStatic += f.getLastStepReport().dropped_static;
		if (k == from) atFrom = allocatedBytes();
	}
	r.growthBytes = allocatedBytes() - atFrom;
	size_t posesKept = 0;
	for (const auto& [obj, tr] : f.getObjectTracks()) posesKept += tr.poses.size();
	const size_t staticKept = allStaticLandmarks(f).size();
	if (recordDropped)
	{
		EXPECT_GE(posesKept, r.droppedPoses);  // every dropped pose is in its track
		EXPECT_GE(staticKept, r.droppedStatic);
	}
	else
	{
		EXPECT_LE(posesKept, 3u * 1u);  // K = 1 pose per object, nothing recorded
		EXPECT_LE(staticKept, 60u);     // only the landmarks in the state
	}
	return r;
}
}  // namespace

TEST(SoakMemory, FlatWithoutRecordsOfDroppedEntries)
{
	const int steps = 6000, from = 1000;
	const TMemoryRun off = runStraight(false, steps, from);
	ASSERT_GT(off.droppedPoses, size_t(steps - from));  // drops happened all along
	ASSERT_GT(off.droppedStatic, size_t(100));
	std::cout << "record_dropped = false: allocated memory grew by " << off.growthBytes
	          << " bytes over " << steps - from << " steps (" << off.droppedPoses << " poses and "
	          << off.droppedStatic << " landmarks dropped)\n";
	// Flat: less than 16 bytes per step (one record of a dropped pose is ~104 bytes).
	EXPECT_LT(off.growthBytes, 16L * (steps - from));

	const TMemoryRun on = runStraight(true, steps, from);
	std::cout << "record_dropped = true: allocated memory grew by " << on.growthBytes << " bytes\n";
	// The records are what grows: at least 50 bytes per dropped pose after step `from`.
	EXPECT_GT(on.growthBytes, 50L * (steps - from));
}

TEST(SoakMemory, RecordDroppedOption)
{
	mrpt::config::CConfigFileMemory ini;
	ini.write("DynamicKFSLAM", "measurement_model", "cartesian");
	ini.write("DynamicKFSLAM", "Sigma_v", "[1e-4 1e-4]");
	CDynamicKFSLAM2D::TOptions o;
	o.loadFromConfigFile(ini, "DynamicKFSLAM");
	EXPECT_TRUE(o.record_dropped);  // default
	ini.write("DynamicKFSLAM", "record_dropped", "false");
	o.loadFromConfigFile(ini, "DynamicKFSLAM");
	EXPECT_FALSE(o.record_dropped);
	ini.write("DynamicKFSLAM", "record_dropped", "sometimes");
	try
	{
		o.loadFromConfigFile(ini, "DynamicKFSLAM");
		ADD_FAILURE() << "record_dropped = sometimes accepted";
	}
	catch (const std::exception& e)
	{
		EXPECT_NE(std::string(e.what()).find("record_dropped"), std::string::npos) << e.what();
	}
}
