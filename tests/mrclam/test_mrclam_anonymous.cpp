/** dynslam-mrclam --anonymous (issue 12; anonymous.h, doc/results/real-data.md section 6): the ID
 * permutation, the rewritten readings, and the class ground truth of every reading, on the
 * shipped excerpt and through the app class. */
#include <dynslam/core/landmark_ids.h>
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/mrclam/CMrclamApp.h>
#include <dynslam/mrclam/CMrclamOptions.h>
#include <dynslam/mrclam/anonymous.h>
#include <dynslam/mrclam/import.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "mini_dataset.h"

using namespace dynslam;
using namespace dynslam::mrclam;

namespace
{
const std::string kExcerpt = std::string(DYNSLAM_DATASETS_DIR) + "/mrclam/MRCLAM_Dataset6_excerpt";

TImportResult importExcerpt()
{
	mrpt::config::CConfigFile ini(std::string(DYNSLAM_CONFIG_DIR) + "/mrclam.ini");
	TMrclamOptions o;
	o.loadFromConfigFile(ini, "MRCLAM_Import");
	return importRobot(loadDataset(kExcerpt, 3), o.import);
}
}  // namespace

TEST(MrclamAnonymous, PermutationOfOneRange)
{
	const auto a = anonymousSubjectIds(1), b = anonymousSubjectIds(1), c = anonymousSubjectIds(2);
	EXPECT_EQ(a, b);  // seeded: reproducible
	EXPECT_NE(a, c);  // and the seed matters
	ASSERT_EQ(a.size(), 20u);
	std::set<int32_t> values;
	for (const auto& [s, id] : a)
	{
		EXPECT_TRUE(isRobotSubject(s) || isLandmarkSubject(s)) << s;
		values.insert(id);
	}
	EXPECT_EQ(values.size(), 20u);
	EXPECT_EQ(*values.begin(), 0);
	EXPECT_EQ(*values.rbegin(), 19);
	// Not the identity nor a shift: some robot gets an ID above some landmark's.
	int32_t maxRobot = -1, minLandmark = 100;
	for (const auto& [s, id] : a)
		(isRobotSubject(s) ? maxRobot : minLandmark) =
		    isRobotSubject(s) ? std::max(maxRobot, id) : std::min(minLandmark, id);
	EXPECT_GT(maxRobot, minLandmark);
	EXPECT_EQ(labelledSubjectId(7), 7);
	EXPECT_EQ(labelledSubjectId(2), ids::objectFeatureId(2, 0));
	EXPECT_THROW(labelledSubjectId(21), std::invalid_argument);
}

TEST(MrclamAnonymous, ExcerptReadingsAndClassTruth)
{
	const TImportResult lab = importExcerpt();
	TImportResult anon = importExcerpt();
	makeAnonymous(anon, 1);
	EXPECT_THROW(makeAnonymous(anon, 1), std::logic_error);
	const auto perm = anonymousSubjectIds(1);
	EXPECT_EQ(anon.summary.anonymous_ids, perm);
	EXPECT_NE(anon.summary.toText().find("anonymous IDs (seed 1)"), std::string::npos);
	EXPECT_EQ(lab.summary.toText().find("anonymous"), std::string::npos);
	ASSERT_EQ(anon.steps.size(), lab.steps.size());
	size_t n = 0, robots = 0;
	for (size_t k = 0; k < anon.steps.size(); ++k)
	{
		ASSERT_EQ(anon.steps[k].meas.size(), lab.steps[k].meas.size());
		for (size_t i = 0; i < anon.steps[k].meas.size(); ++i, ++n)
		{
			const auto &a = anon.steps[k].meas[i], &l = lab.steps[k].meas[i];
			EXPECT_EQ(a.subject, l.subject);  // only the ID changes
			EXPECT_EQ(a.range, l.range);
			EXPECT_EQ(a.bearing, l.bearing);
			EXPECT_EQ(a.id, perm.at(a.subject));
			EXPECT_TRUE(a.id >= 0 && a.id < 20);
			EXPECT_EQ(l.id, labelledSubjectId(l.subject));
			robots += isRobotSubject(a.subject);
		}
	}
	ASSERT_EQ(anon.gt.landmarks.size(), 15u);
	for (const auto& [s, p] : lab.gt.landmarks) EXPECT_EQ(anon.gt.landmarks.at(perm.at(s)), p);
	EXPECT_EQ(n, 800u);  // the excerpt's 800 measurements (datasets/mrclam/README.md)
	EXPECT_EQ(robots, 245u);
	const std::vector<io::TReadingClass> truth = classGroundTruth(anon);
	ASSERT_EQ(truth.size(), n);
	size_t moving = 0, row = 0;
	for (size_t k = 0; k < anon.steps.size(); ++k)
		for (size_t i = 0; i < anon.steps[k].meas.size(); ++i, ++row)
		{
			const io::TReadingClass& r = truth[row];
			const int s = anon.steps[k].meas[i].subject;
			EXPECT_EQ(r.step, int(k));
			EXPECT_EQ(r.index, int(i));
			EXPECT_EQ(r.t, anon.steps[k].t);
			EXPECT_EQ(r.id, perm.at(s));
			EXPECT_EQ(r.true_id, labelledSubjectId(s));
			EXPECT_EQ(r.cls, isRobotSubject(s) ? io::TrueClass::Moving : io::TrueClass::Static);
			EXPECT_EQ(r.object, isRobotSubject(s) ? s : -1);
			moving += r.cls == io::TrueClass::Moving;
		}
	EXPECT_EQ(moving, 245u);
}

TEST(MrclamAnonymous, AppWritesAnonymousRawlogAndClassTruth)
{
	const std::string out = mrclam_test::tempDir("anon_app");
	CMrclamApp app;
	app.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const std::string cfg = std::string(DYNSLAM_CONFIG_DIR) + "/mrclam.ini";
	const char* argv[] = {
	    "dynslam-mrclam", "--dataset", kExcerpt.c_str(), "--robot", "3", "--out",      out.c_str(),
	    "--config",       cfg.c_str(), "--anonymous",    "--seed",  "7", "--duration", "20"};
	ASSERT_TRUE(app.initialize(int(std::size(argv)), argv));
	app.run();
	EXPECT_EQ(app.summary.anonymous_ids, anonymousSubjectIds(7));
	const auto truth = io::readClassGroundTruth(out + "/robot3_gt_classes.csv");
	EXPECT_EQ(truth.size(), app.summary.kept);
	for (const auto& r : truth)
		EXPECT_EQ(r.id, anonymousSubjectIds(7).at(r.object >= 0 ? r.object : r.feature));
	std::ifstream ini(out + "/robot3_import.ini");
	std::stringstream ss;
	ss << ini.rdbuf();
	EXPECT_NE(ss.str().find("ids = anonymous\nanonymous_seed = 7\n"), std::string::npos);
	// --seed without --anonymous, --anonymous with --estimate-noise: errors.
	CMrclamApp bad;
	const char* argv2[] = {"dynslam-mrclam", "--dataset", kExcerpt.c_str(), "--robot", "3",
	                       "--out",          out.c_str(), "--seed",         "3"};
	EXPECT_THROW(bad.initialize(int(std::size(argv2)), argv2), std::invalid_argument);
	CMrclamApp bad2;
	const char* argv3[] = {"dynslam-mrclam",   "--dataset",  kExcerpt.c_str(), "--robot", "3",
	                       "--estimate-noise", "--anonymous"};
	EXPECT_THROW(bad2.initialize(int(std::size(argv3)), argv3), std::invalid_argument);
	std::filesystem::remove_all(out);
}
