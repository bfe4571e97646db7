/** dynslam-run's timing.csv and the peak memory in metrics.csv (issue 29, item 4): the app
 * class driven directly on the shipped highway dataset, the state sizes checked against an
 * independent replay of the same back-end, the peak memory against the kernel's VmRSS / VmHWM
 * read by the test. */
#include <apps_test_utils.h>
#include <dynslam/apps/CRunApp.h>
#include <dynslam/apps/filter_run.h>
#include <dynslam/apps/rawlog_io.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace dynslam;
using namespace dynslam::apps;
using apps_test::TArgs;

namespace
{
/** A "VmRSS:" / "VmHWM:" line of /proc/self/status in MiB; NaN if absent. */
double procStatusMb(const std::string& key)
{
	std::ifstream is("/proc/self/status");
	std::string line;
	while (std::getline(is, line))
		if (line.rfind(key, 0) == 0)
		{
			std::istringstream ls(line.substr(key.size()));
			double kb = 0;
			ls >> kb;
			return kb / 1024.0;
		}
	return std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::vector<std::string>> readCsv(const std::string& path, std::string& header)
{
	const auto lines = apps_test::readLines(path);
	std::vector<std::vector<std::string>> rows;
	if (lines.empty()) return rows;
	header = lines[0];
	for (size_t i = 1; i < lines.size(); ++i)
		if (!lines[i].empty()) rows.push_back(apps_test::splitCsv(lines[i]));
	return rows;
}

/** Objects with a block in the state: a feature or a pose in it. */
size_t liveObjects(const ISlamBackend& b)
{
	std::set<int32_t> objs;
	for (const auto& f : b.getObjectFeatures()) objs.insert(f.object);
	for (const auto& [obj, track] : b.getObjectTracks())
		for (const auto& p : track.poses)
			if (p.in_state) objs.insert(obj);
	return objs.size();
}
}  // namespace

TEST(TimingCsv, OneRowPerStepWithTheFiltersStateSizesAndPeakMemoryInMetrics)
{
	const std::string out = apps_test::freshDir("timing");
	const double rssBefore = procStatusMb("VmRSS:");
	CRunApp app;
	TArgs a({"-c", apps_test::configFile("run_highway.ini"), "-o", out, "-q", "--no-figures"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	const double hwmAfter = procStatusMb("VmHWM:");

	std::string header;
	const auto rows = readCsv(out + "/timing.csv", header);
	EXPECT_EQ(header, "step,ms,static_landmarks,live_objects,state_dim");
	ASSERT_EQ(rows.size(), 121u);
	// The same back-end replayed: its state after every step.
	auto backend = makeBackend(app.backend, app.params);
	const auto* ekf = dynamic_cast<const CDynamicKFSLAM2D*>(backend.get());
	ASSERT_NE(ekf, nullptr);
	const TRawlog log = loadRawlog(app.rawlogFile);
	double sumMs = 0;
	size_t maxObjects = 0;
	for (size_t k = 0; k < rows.size(); ++k)
	{
		const auto& r = rows[k];
		ASSERT_EQ(r.size(), 5u) << "row " << k;
		EXPECT_EQ(std::stoul(r[0]), k);
		const double ms = std::stod(r[1]);
		EXPECT_GT(ms, 0.0) << "step " << k;
		sumMs += ms;
		backend->processActionObservation(log.actions[k], log.frames[k]);
		EXPECT_EQ(std::stoul(r[2]), backend->getStaticLandmarks().size()) << "step " << k;
		EXPECT_EQ(std::stoul(r[3]), liveObjects(*backend)) << "step " << k;
		EXPECT_EQ(std::stoul(r[4]), ekf->fullMean().size()) << "step " << k;
		maxObjects = std::max(maxObjects, liveObjects(*backend));
	}
	EXPECT_EQ(maxObjects, 3u);  // the highway's two cars and the pedestrian
	// The rows are the run's own times (6 decimals per row) and its final map.
	EXPECT_NEAR(sumMs, app.result.total_ms, 1e-3);
	EXPECT_EQ(std::stoul(rows.back()[2]), app.result.est.landmarks.size());
	EXPECT_GT(app.result.est.landmarks.size(), 50u);

	// metrics.csv: peak_rss_mb, the last column; at least the memory in use before the run and
	// at most the peak the kernel reports after it (the same process).
	const auto m = readCsv(out + "/metrics.csv", header);
	ASSERT_EQ(m.size(), 1u);
	const auto cols = apps_test::splitCsv(header);
	ASSERT_EQ(cols.back(), "peak_rss_mb");
	ASSERT_EQ(m[0].size(), cols.size());
	const double peak = std::stod(m[0].back());
	std::cout << "peak_rss_mb " << peak << " (VmRSS before the run " << rssBefore
	          << ", VmHWM after " << hwmAfter << ")\n";
	EXPECT_GT(peak, 0.0);
	EXPECT_GE(peak, rssBefore - 0.01);
	EXPECT_LE(peak, hwmAfter + 0.01);
}

TEST(TimingCsv, WrittenWithoutGroundTruthAndForTheStaticBackendNoTemporaryFileLeft)
{
	const std::string out = apps_test::freshDir("timing_static");
	CRunApp app;
	TArgs a({"-c", apps_test::configFile("run_highway.ini"), "-o", out, "--no-gt", "--backend",
	         "static_landmarks_only", "--no-figures", "-q"});
	ASSERT_TRUE(app.initialize(a.argc(), a.argv()));
	app.run();
	EXPECT_FALSE(std::filesystem::exists(out + "/metrics.csv"));
	std::string header;
	const auto rows = readCsv(out + "/timing.csv", header);
	ASSERT_EQ(rows.size(), 121u);
	for (const auto& r : rows)
	{
		ASSERT_EQ(r.size(), 5u);
		EXPECT_GT(std::stod(r[1]), 0.0);
		EXPECT_EQ(r[3], "0");  // the static filter has no objects
		EXPECT_EQ(r[4], "");   // and reports no state dimension
	}
	EXPECT_EQ(std::stoul(rows.back()[2]), app.result.est.landmarks.size());
	// The temporary file was moved, not copied and left behind.
	const std::string prefix = "dynslam-run-timing-" + std::to_string(::getpid()) + "-";
	for (const auto& e :
	     std::filesystem::directory_iterator(std::filesystem::temp_directory_path()))
		EXPECT_NE(e.path().filename().string().rfind(prefix, 0), 0u) << e.path();
}
