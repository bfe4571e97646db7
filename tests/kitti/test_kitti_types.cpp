/** Every KITTI type is accepted by the label reader (issue 31: `Person`, the tracking labels'
 * sitting person, was rejected); a type that is not a KITTI type is kept, counted and reported
 * in the summary, not an error. Hand-written label lines (kitti_test::labelLine). */
#include <dynslam/kitti/CKittiApp.h>
#include <dynslam/kitti/kitti_files.h>
#include <gtest/gtest.h>

#include "mini_sequence.h"

using namespace dynslam::kitti;

TEST(KittiTypes, EveryKittiTypeIsAccepted)
{
	const std::vector<std::string> types = {
	    "Car", "Van", "Truck", "Pedestrian", "Person", "Person_sitting", "Cyclist", "Tram", "Misc"};
	std::vector<std::string> lines;
	for (size_t i = 0; i < types.size(); ++i)
	{
		EXPECT_TRUE(isKnownType(types[i])) << types[i];
		// one box per type in frame 0, each its own track, 5 m apart across the road
		lines.push_back(kitti_test::labelLine(0, int(i), types[i], -20.0 + 5.0 * double(i), 30, 0));
	}
	lines.push_back("0 -1 DontCare -1 -1 -10 1 2 3 4 -1000 -1000 -1000 -10 -1 -1 -1");
	EXPECT_TRUE(isKnownType("DontCare"));
	const std::string d = kitti_test::writeMiniSequence("types", 2, lines);
	const TKittiLabels L = readLabels(d + "/label_02/0007.txt");
	EXPECT_EQ(L.boxes.size(), types.size());
	EXPECT_EQ(L.dontcare, 1u);
	EXPECT_TRUE(L.unknown_types.empty());
	ASSERT_EQ(L.types.size(), types.size());
	for (const auto& t : types) EXPECT_EQ(L.types.at(t), 1u) << t;
	const TImportResult res = importFromFiles(d + "/label_02", d + "/poses", "0007", {});
	EXPECT_EQ(res.summary.boxes, types.size());
	EXPECT_NE(res.summary.toText().find("Person 1, Person_sitting 1"), std::string::npos)
	    << res.summary.toText();
	EXPECT_NE(res.summary.toText().find("(kept as boxes): none"), std::string::npos);
}

TEST(KittiTypes, AnUnknownTypeIsCountedAndReported)
{
	auto lines = kitti_test::miniLabels();
	// replace the pedestrian (track 2) of frames 0 and 1 by a "Bus" and a "car" (lower case: not
	// a KITTI type either); the boxes stay, with their track
	lines[3] = kitti_test::labelLine(0, 2, "Bus", 20, 3.0, 0, 0.8, 0.6);
	lines[7] = kitti_test::labelLine(1, 2, "car", 20, 3.0, 0, 0.8, 0.6);
	EXPECT_FALSE(isKnownType("Bus"));
	EXPECT_FALSE(isKnownType("car"));
	const std::string d = kitti_test::writeMiniSequence("unknown_type", 12, lines);
	const TKittiLabels L = readLabels(d + "/label_02/0007.txt");
	EXPECT_EQ(L.unknown_types.size(), 2u);
	EXPECT_EQ(L.unknown_types.at("Bus"), 1u);
	EXPECT_EQ(L.unknown_types.at("car"), 1u);
	EXPECT_EQ(L.types.at("Pedestrian"), 10u);
	const TImportResult res = importFromFiles(d + "/label_02", d + "/poses", "0007", {});
	EXPECT_EQ(res.summary.boxes, L.boxes.size());
	EXPECT_EQ(res.summary.unknown_types.at("Bus"), 1u);
	const std::string text = res.summary.toText();
	EXPECT_NE(text.find("not KITTI types (kept as boxes): Bus 1, car 1"), std::string::npos)
	    << text;
}
