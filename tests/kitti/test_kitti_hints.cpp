/** The importer's optional hint output (detection_groups = true): every corner's detection
 * group is its KITTI track ID, read back through the one step parser
 * (dynslam/common/detection_groups.h, doc/results/classification.md "Hints and links after a track
 * break"). */
#include <dynslam/common/step_input.h>
#include <dynslam/kitti/import.h>
#include <dynslam/kitti/kitti_files.h>
#include <dynslam/kitti/rawlog_writer.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CRawlog.h>

#include <filesystem>

#include "mini_sequence.h"

using namespace dynslam;
using namespace dynslam::kitti;

TEST(KittiHints, CornersCarryTheirTrackIdAsHint)
{
	const std::string d = kitti_test::writeMiniSequence("hints", 12);
	const auto poses = readPoses(d + "/poses/0007.txt");
	const auto labels = readLabels(d + "/label_02/0007.txt");
	for (const bool groups : {false, true})
	{
		TImportOptions o;
		o.anonymous = true;
		o.detection_groups = groups;
		const TImportResult res = importSequence(poses, labels, o, "0007");
		const std::string path = d + "/hints_" + std::to_string(groups) + ".rawlog";
		writeRawlog(res, o, path);
		mrpt::obs::CRawlog log;
		ASSERT_TRUE(log.loadFromRawLogFile(path));
		ASSERT_EQ(log.size(), 2 * res.steps.size());
		size_t hinted = 0;
		for (size_t k = 0; k < res.steps.size(); ++k)
		{
			const auto in = parseStepInput(log.getAsAction(2 * k), log.getAsObservations(2 * k + 1),
			                               TParseOptions(), "test");
			const auto& rd = res.steps[k].readings;
			ASSERT_EQ(in.readings.size(), rd.size());
			for (size_t i = 0; i < rd.size(); ++i)
			{
				EXPECT_EQ(in.readings[i].id, rd[i].id);
				EXPECT_EQ(in.readings[i].hint, groups ? rd[i].track : -1) << "step " << k;
				hinted += in.readings[i].hint >= 0;
			}
		}
		if (groups)
		{
			EXPECT_GT(hinted, 0u);
		}
	}
}
