/** eval::gapMetrics (issue 13, doc/metrics.md "Inside a landmark gap"): ATE inside and outside
 * a landmark gap on the true ego x, the error at the gap's last step, and the mean ego NEES
 * over the gap with its chi-square bounds; values computed by hand. */
#include <dynslam/eval/chi2.h>
#include <dynslam/eval/gap_figure.h>
#include <dynslam/eval/gap_metrics.h>
#include <dynslam/eval/writers.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace dynslam;
using namespace dynslam::eval;

namespace
{
io::TGroundTruth straightRoad()
{
	io::TGroundTruth gt;
	for (int k = 0; k < 6; ++k)
	{
		gt.t.push_back(0.5 * k);
		gt.ego.emplace_back(10.0 * k, 0, 0);  // x = 0, 10, ..., 50
	}
	return gt;
}

TEgoEstimate estimate(int step, const Eigen::Vector3d& truth, const Eigen::Vector3d& err,
                      double var)
{
	TEgoEstimate e;
	e.step = step;
	e.mean = truth + err;
	e.cov = Eigen::Matrix3d::Identity() * var;
	return e;
}
}  // namespace

TEST(GapMetrics, InsideOutsideEndAndNees)
{
	const io::TGroundTruth gt = straightRoad();
	std::vector<TEgoEstimate> ego;
	// Gap [15, 35]: steps 2 (x = 20) and 3 (x = 30). Errors 0.3 / 0.4 m inside, 0.1 outside.
	for (int k = 0; k < 6; ++k)
	{
		const double d = k == 2 ? 0.3 : k == 3 ? 0.4 : 0.1;
		ego.push_back(estimate(k, gt.ego[size_t(k)], Eigen::Vector3d(0, d, 0), 0.01));
	}
	ego.back().step = 9;  // outside the ground truth: ignored
	const TGapMetrics g = gapMetrics(gt, ego, {{15, 35}});
	EXPECT_EQ(g.steps, 2u);
	EXPECT_NEAR(g.ate, std::sqrt((0.09 + 0.16) / 2), 1e-12);
	EXPECT_NEAR(g.ate_outside, 0.1, 1e-12);
	EXPECT_NEAR(g.err_end, 0.4, 1e-12);  // step 3, the last one in the gap
	// NEES: 0.09 / 0.01 = 9 and 16: mean 12.5; bounds chi2(6) 2.5 / 97.5 % / 2.
	EXPECT_EQ(g.nees_steps, 2u);
	EXPECT_NEAR(g.nees, 12.5, 1e-9);
	EXPECT_NEAR(g.nees_lower, chi2Quantile(0.025, 6) / 2, 1e-12);
	EXPECT_NEAR(g.nees_upper, chi2Quantile(0.975, 6) / 2, 1e-12);
	EXPECT_NEAR(g.nees_lower, 1.2373 / 2, 1e-4);  // tables: chi2(6) 2.5 % = 1.2373
}

TEST(GapMetrics, NoGapStepOrSingularCovariance)
{
	const io::TGroundTruth gt = straightRoad();
	std::vector<TEgoEstimate> ego;
	for (int k = 0; k < 6; ++k) ego.push_back(estimate(k, gt.ego[size_t(k)], {0.1, 0, 0}, 0.0));
	const TGapMetrics none = gapMetrics(gt, ego, {{100, 200}});
	EXPECT_EQ(none.steps, 0u);
	EXPECT_TRUE(std::isnan(none.ate));
	EXPECT_TRUE(std::isnan(none.nees));
	EXPECT_NEAR(none.ate_outside, 0.1, 1e-12);
	// Zero covariances: the ATE is scored, the NEES is not (no NaN/Inf from a singular P).
	const TGapMetrics z = gapMetrics(gt, ego, {{-1, 25}});
	EXPECT_EQ(z.steps, 3u);
	EXPECT_EQ(z.nees_steps, 0u);
	EXPECT_TRUE(std::isnan(z.nees));
}

TEST(GapMetrics, MetricsCsvColumnsOnlyWhenARowHasThem)
{
	std::vector<TMetricsRow> rows(2);
	rows[0].filter = "a";
	rows[1].filter = "b";
	const auto header = [&]
	{
		std::ostringstream os;
		writeMetricsCsv(os, rows);
		return os.str();
	};
	EXPECT_EQ(header().find("ate_gap"), std::string::npos);
	TGapMetrics g;
	g.steps = 7;
	g.ate = 0.25;
	rows[0].gap = g;
	const std::string csv = header();
	std::istringstream in(csv);
	std::string h, r0, r1;
	std::getline(in, h);
	std::getline(in, r0);
	std::getline(in, r1);
	const std::string cols =
	    "ate_gap,ate_outside_gap,err_gap_end,steps_gap,ego_nees_gap,ego_nees_gap_lower,"
	    "ego_nees_gap_upper";
	ASSERT_GE(h.size(), cols.size());
	EXPECT_EQ(h.substr(h.size() - cols.size()), cols);
	EXPECT_NE(r0.find(",0.25,,,7,"), std::string::npos) << r0;  // NaN cells are empty
	EXPECT_EQ(r1.substr(r1.size() - 7), ",,,,,,,");
}

TEST(GapMetrics, ErrorOverTheRoadFigureShadesTheGap)
{
	const io::TGroundTruth gt = straightRoad();
	TRunEstimates est;
	for (int k = 0; k < 6; ++k)
		est.ego.push_back(estimate(k, gt.ego[size_t(k)], Eigen::Vector3d(0, 0.1 * k, 0), 0.01));
	const mrpt::img::TColor blue(0, 0, 255);
	const mrpt::img::CImage img = drawGapErrorFigure(gt, {{"f", blue, &est}}, {{15, 35}}, 800, 400);
	ASSERT_EQ(img.getWidth(), 800u);
	ASSERT_EQ(img.getHeight(), 400u);
	// x from -1 to 51 m (2 % margins) over the plot columns 80..622 (the legend, 12 characters
	// wide, "landmark gap", sits right of the plot: 40 + 9 * 12 + 10 pixels and 20 of margin);
	// the gap 15..35 m is checked 1 m inside its edges, the rest 1 m outside them.
	const int right = 800 - (40 + 9 * 12 + 10) - 20;
	size_t shaded = 0, shadedOutside = 0, line = 0;
	for (int y = 45; y < 340; ++y)
		for (int x = 85; x < right - 5; ++x)
		{
			const uint8_t* p = img(x, y);                                 // BGR
			const bool grey = p[0] == 205 && p[1] == 230 && p[2] == 235;  // BGR of the shade
			const double wx = -1.0 + 52.0 * (x - 80) / double(right - 80);
			if (grey && wx > 16 && wx < 34) ++shaded;
			if (grey && (wx < 14 || wx > 36)) ++shadedOutside;
			if (p[0] == 255 && p[1] == 0 && p[2] == 0) ++line;
		}
	EXPECT_GT(shaded, 40000u);  // most of the gap's columns (about 190) x rows (295)
	EXPECT_EQ(shadedOutside, 0u);
	EXPECT_GT(line, 300u);  // the series is drawn
}
