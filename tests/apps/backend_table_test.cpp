/** The back-end table on a small Monte Carlo (2 runs, 40 steps of the highway): every
 * back-end runs, its errors are finite and small, and the full smoother (vdo) is at least as
 * accurate as the EKF-equivalent Alg. 1 on the ego trajectory. */
#include <dynslam/apps/backend_table.h>
#include <gtest/gtest.h>

#include <iostream>

using namespace dynslam::apps;

TEST(BackendTable, SmallMonteCarlo)
{
	TBackendTableOptions o;
	o.scenario_ini = std::string(DYNSLAM_CONFIG_DIR) + "/highway.ini";
	o.runs = 2;
	o.steps = 40;
	const auto rows = runBackendTable(o);
	writeBackendTableMarkdown(std::cout, rows);
	ASSERT_EQ(rows.size(), 7u);
	std::map<std::string, TBackendTableRow> by;
	for (const auto& r : rows)
	{
		by[r.kind] = r;
		EXPECT_EQ(r.failures, 0) << r.kind << ": " << r.failure;
		EXPECT_EQ(r.runs, 2) << r.kind;
		EXPECT_LT(r.ego_x, 0.1) << r.kind;
		EXPECT_LT(r.map_x, 0.1) << r.kind;
		EXPECT_LT(r.pose_x, 0.2) << r.kind;
	}
	// Alg. 1 is the EKF: identical estimates.
	EXPECT_NEAR(by["alg1"].ego_x, by["dynamic_ekf"].ego_x, 1e-9);
	EXPECT_NEAR(by["alg1"].pose_x, by["dynamic_ekf"].pose_x, 1e-9);
}
