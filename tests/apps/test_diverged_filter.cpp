/** dynslam-compare when one filter diverges (its ego mean becomes NaN, as MRPT's
 * static_landmarks_only does on KITTI 0007, doc/kitti.md 5.5): the other rows are still
 * computed and written, the diverged filter is named under the table and in
 * OUT/failed_filters.txt. Provoked here: MRPT's filter with a range noise (1e-45: the smallest
 * float) whose variance underflows to 0 on exact odometry (zero covariance), so its innovation
 * covariance is singular at the second sighting of a landmark. */
#include <apps_test_utils.h>
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/common/rawlog_file_writer.h>
#include <dynslam_test/scripted_steps.h>

#include <regex>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::TArgs;

namespace
{
/** 60 steps along x at 1 m per step among 6 landmarks: exact odometry (zero covariance) for
 * the first 3 steps, then a small odometry noise. */
std::string writeRawlog(const std::string& dir)
{
	namespace S = dynslam_test::script;
	const std::string path = dir + "/exact.rawlog";
	CRawlogFileWriter w(path, "test");
	for (int k = 0; k < 60; ++k)
	{
		S::TSeen seen;
		for (int i = 0; i < 6; ++i) seen.emplace_back(i, Eigen::Vector2d(3.0 * i, i % 2 ? 4 : -4));
		w.writeStep(*S::action(k == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(1, 0, 0),
		                       Eigen::Matrix3d(Eigen::Matrix3d::Identity() * (k < 3 ? 0.0 : 1e-4))),
		            *S::frame(Eigen::Vector3d(k, 0, 0), seen));
	}
	w.close();
	return path;
}
}  // namespace

TEST(CompareApp, ADivergedFilterIsNamedAndTheOthersRunOn)
{
	const std::string dir = apps_test::freshDir("diverged");
	const std::string rawlog = writeRawlog(dir);
	std::string ini = apps_test::shippedIniText("compare_highway.ini");
	ini = std::regex_replace(ini, std::regex("\\n(std_sensor_range *=)[^\\n]*"), "\n$1 1e-45");
	apps_test::writeFile(dir + "/compare.ini", ini);
	CCompareApp app;
	TArgs a({"-c", dir + "/compare.ini", "-r", rawlog, "--no-gt", "--filters",
	         "static_all, dynamic", "--no-figures", "-q", "--out", dir + "/out"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	ASSERT_EQ(app.failedFilters.size(), 1u);
	EXPECT_EQ(app.failedFilters[0].rfind("static_all: diverged (ego mean at step", 0), 0u)
	    << app.failedFilters[0];
	ASSERT_EQ(app.rows.size(), 1u);
	EXPECT_EQ(app.rows[0].filter, "dynamic");
	ASSERT_EQ(app.runs.size(), 1u);
	EXPECT_NE(app.tableText.find("NOT IN THE TABLE: static_all: diverged"), std::string::npos);
	EXPECT_EQ(apps_test::readFile(dir + "/out/failed_filters.txt"), app.failedFilters[0] + "\n");
	// every filter diverging is an error, not an empty table
	CCompareApp only;
	TArgs b({"-c", dir + "/compare.ini", "-r", rawlog, "--no-gt", "--filters", "static_all",
	         "--no-figures", "-q"});
	ASSERT_TRUE(only.initialize(b.argc(), b.argv()));
	EXPECT_THROW(only.run(), std::runtime_error);
}
