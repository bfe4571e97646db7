/** The mode-probability figure (eval::drawModeFigure, issue 28 item 5): one panel per object, a
 * line per mode whose pixels follow its probability (a mode at probability 1 throughout is drawn
 * at the top of its panel, one at 0 at the bottom); no figure without mode probabilities. */
#include <dynslam/eval/figures.h>
#include <dynslam/eval/mode_figure.h>
#include <gtest/gtest.h>

using namespace dynslam::eval;

namespace
{
/** Rows (y) where colour c appears in column x. */
std::vector<int> rowsOf(const mrpt::img::CImage& img, int x, const mrpt::img::TColor& c)
{
	std::vector<int> rows;
	for (int y = 0; y < int(img.getHeight()); ++y)
	{
		const uint8_t* p = img(x, y);  // BGR
		if (p[2] == c.R && p[1] == c.G && p[0] == c.B) rows.push_back(y);
	}
	return rows;
}

TRunEstimates twoObjects()
{
	TRunEstimates est;
	est.object_mode_names = {"a", "b"};
	for (int k = 0; k < 50; ++k)
		for (int obj : {3, 7})
		{
			TObjectPoseEstimate p;
			p.object = obj;
			p.step = k;
			p.mean = Eigen::Vector3d::Zero();
			p.cov = Eigen::Matrix3d::Identity();
			p.mode_probabilities = obj == 3 ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
			est.object_poses.push_back(p);
		}
	return est;
}
}  // namespace

TEST(ModeFigure, OnePanelPerObjectLinesAtTheirProbabilities)
{
	const TRunEstimates est = twoObjects();
	ASSERT_TRUE(hasModeProbabilities(est));
	TModeFigureOptions o;
	const mrpt::img::CImage img = drawModeFigure(est, o);
	EXPECT_EQ(int(img.getWidth()), o.width);
	EXPECT_EQ(int(img.getHeight()), 40 + 2 * (o.panel_height + 45) + 15);
	const int x = o.width / 3;  // inside both plot areas
	const auto a = rowsOf(img, x, seriesColor(0)), b = rowsOf(img, x, seriesColor(1));
	ASSERT_FALSE(a.empty());
	ASSERT_FALSE(b.empty());
	// Object 3 (first panel): mode a at 1 (top), b at 0 (bottom); object 7: the reverse.
	const int panel1 = 40, panel2 = 40 + o.panel_height + 45;
	const auto inPanel = [&](const std::vector<int>& rows, int top)
	{
		std::vector<int> r;
		for (int y : rows)
			if (y >= top && y < top + o.panel_height) r.push_back(y - top);
		return r;
	};
	const auto a1 = inPanel(a, panel1), b1 = inPanel(b, panel1);
	const auto a2 = inPanel(a, panel2), b2 = inPanel(b, panel2);
	ASSERT_FALSE(a1.empty() || b1.empty() || a2.empty() || b2.empty());
	EXPECT_LT(a1.back(), o.panel_height / 10);       // P = 1: near the top
	EXPECT_GT(b1.front(), 9 * o.panel_height / 10);  // P = 0: near the bottom
	EXPECT_GT(a2.front(), 9 * o.panel_height / 10);
	EXPECT_LT(b2.back(), o.panel_height / 10);
}

TEST(ModeFigure, NoModeProbabilitiesNoFigure)
{
	TRunEstimates est = twoObjects();
	est.object_mode_names.clear();
	EXPECT_FALSE(hasModeProbabilities(est));
	EXPECT_THROW(drawModeFigure(est), std::invalid_argument);
	est = twoObjects();
	for (auto& p : est.object_poses) p.mode_probabilities.resize(0);
	EXPECT_FALSE(hasModeProbabilities(est));
}
