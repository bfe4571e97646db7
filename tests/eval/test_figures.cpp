// Headless figures: PNG files of the expected size with drawn (non-background) pixels.
#include <dynslam/eval/figures.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

using namespace dynslam::eval;

namespace
{
/** A highway-like scene: 1 km x ~60 m, 121 steps, two objects. */
dynslam::io::TGroundTruth highway()
{
	dynslam::io::TGroundTruth gt;
	for (int k = 0; k <= 120; ++k)
	{
		gt.t.push_back(0.5 * k);
		const double y = k < 60 ? 0.0 : std::min(3.5, 0.2 * (k - 60));
		gt.ego.emplace_back(8.3 * k, y, 0.0);
	}
	for (int i = 0; i < 40; ++i) gt.landmarks[i] = Eigen::Vector2d(25.0 * i, i % 2 ? 25 : -25);
	for (int o = 0; o < 2; ++o)
	{
		dynslam::io::TObjectGroundTruth ob;
		ob.object = o;
		ob.num_features = 2;
		ob.first_step = 0;
		for (int k = 0; k <= 120; ++k)
		{
			const Eigen::Vector2d c(20.0 + 8.0 * k, o == 0 ? 3.5 : -3.5 + 0.05 * k);
			Eigen::Matrix2Xd f(2, 2);
			f.col(0) = c + Eigen::Vector2d(-2, 0);
			f.col(1) = c + Eigen::Vector2d(2, 0);
			ob.features.push_back(f);
			ob.pose.push_back(Eigen::Vector3d(8.0 * k, o == 0 ? 0.0 : 0.05 * k, 0.0));
			ob.visible.push_back(1);
		}
		gt.objects.push_back(ob);
	}
	return gt;
}

TRunEstimates noisyRun(const dynslam::io::TGroundTruth& gt, unsigned seed, double sigma)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> n(0.0, sigma);
	TRunEstimates est;
	for (size_t k = 0; k < gt.ego.size(); ++k)
	{
		TEgoEstimate e;
		e.step = static_cast<int>(k);
		e.mean = gt.ego[k] + Eigen::Vector3d(n(rng), n(rng), 0.01 * n(rng));
		e.cov = Eigen::Vector3d(sigma * sigma, sigma * sigma, 1e-4 * sigma * sigma).asDiagonal();
		est.ego.push_back(e);
	}
	for (const auto& [id, p] : gt.landmarks)
		est.landmarks.push_back(
		    {id, p + Eigen::Vector2d(n(rng), n(rng)), sigma * sigma * Eigen::Matrix2d::Identity()});
	for (const auto& o : gt.objects)
	{
		for (int j = 0; j < o.num_features; ++j)
			est.object_features.push_back(
			    {o.object, j, o.features[0].col(j), 0.01 * Eigen::Matrix2d::Identity()});
		for (size_t k = 0; k < o.pose.size(); k += 2)
		{
			TObjectPoseEstimate p;
			p.object = o.object;
			p.step = static_cast<int>(k);
			p.mean = o.pose[k] + Eigen::Vector3d(n(rng), n(rng), 0.0);
			p.cov = 0.01 * Eigen::Matrix3d::Identity();
			est.object_poses.push_back(p);
		}
	}
	return est;
}

std::string outDir()
{
	const std::string d = std::string(DYNSLAM_BINARY_DIR) + "/test_eval_figures";
	std::filesystem::create_directories(d);
	return d;
}

/** Number of pixels that are not the white background, and of pixels of colour c. */
std::pair<size_t, size_t> countPixels(const mrpt::img::CImage& img, const mrpt::img::TColor& c)
{
	size_t drawn = 0, match = 0;
	for (int y = 0; y < static_cast<int>(img.getHeight()); ++y)
		for (int x = 0; x < static_cast<int>(img.getWidth()); ++x)
		{
			const uint8_t* p = img(x, y);  // BGR
			if (p[0] != 255 || p[1] != 255 || p[2] != 255) ++drawn;
			if (p[2] == c.R && p[1] == c.G && p[0] == c.B) ++match;
		}
	return {drawn, match};
}

mrpt::img::CImage saveAndReload(const mrpt::img::CImage& img, const std::string& name)
{
	const std::string path = outDir() + "/" + name;
	std::filesystem::remove(path);
	savePng(img, path);
	EXPECT_TRUE(std::filesystem::exists(path));
	mrpt::img::CImage back;
	EXPECT_TRUE(back.loadFromFile(path));
	return back;
}
}  // namespace

TEST(Figures, MapFigurePngWithTwoFilters)
{
	const auto gt = highway();
	const auto a = noisyRun(gt, 1, 0.5), b = noisyRun(gt, 2, 1.5);
	const std::vector<TFigureSeries> s = {{"dynamic", seriesColor(0), &a},
	                                      {"static_all", seriesColor(1), &b}};
	const auto img = saveAndReload(drawMapFigure(&gt, s), "map.png");
	EXPECT_EQ(img.getWidth(), 1600u);
	EXPECT_EQ(img.getHeight(), 700u);
	const auto [drawn, red] = countPixels(img, seriesColor(0));
	EXPECT_GT(drawn, 20000u);  // paths, ellipses, marks, axes, legend
	EXPECT_GT(red, 1000u);     // the first filter's colour is there
	EXPECT_LT(drawn, 1600u * 700u / 2);

	TMapFigureOptions zoom;
	zoom.width = 800;
	zoom.height = 400;
	zoom.view = TBox{400, 600, -30, 30};
	zoom.equal_aspect = true;
	const auto z = saveAndReload(drawMapFigure(&gt, s, zoom), "map_zoom.png");
	EXPECT_EQ(z.getWidth(), 800u);
	EXPECT_EQ(z.getHeight(), 400u);
	EXPECT_GT(countPixels(z, seriesColor(1)).second, 200u);
}

TEST(Figures, ErrorAndConsistencyFigures)
{
	const auto gt = highway();
	const auto a = noisyRun(gt, 3, 0.3);
	const auto img =
	    saveAndReload(drawEgoErrorFigure(gt, {{"dynamic", seriesColor(0), &a}}), "ego_errors.png");
	EXPECT_EQ(img.getWidth(), 1400u);
	EXPECT_EQ(img.getHeight(), 900u);
	const auto [drawn, red] = countPixels(img, seriesColor(0));
	EXPECT_GT(drawn, 10000u);
	EXPECT_GT(red, 1000u);

	const auto rc = computeRunConsistency(gt, a);
	const auto sum = summarizeConsistency({rc});
	const auto c = saveAndReload(drawConsistencyFigure(sum.ego), "ego_nees.png");
	EXPECT_EQ(c.getWidth(), 1200u);
	EXPECT_EQ(c.getHeight(), 500u);
	EXPECT_GT(countPixels(c, seriesColor(1)).second, 500u);
}

TEST(Figures, CanvasScalingAndClipping)
{
	mrpt::img::CImage img(400, 300, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, 399, 299, mrpt::img::TColor(255, 255, 255));
	// 1000 m x 60 m into 400 x 200 px: non-uniform fills both axes ...
	CPlotCanvas fill(img, 0, 0, 400, 200, TBox{0, 1000, -30, 30}, false);
	EXPECT_NEAR(fill.px(1000) - fill.px(0), 400, 1e-9);
	EXPECT_NEAR(fill.py(-30) - fill.py(30), 200, 1e-9);
	// ... equal aspect keeps metres square (the lateral extent shrinks to 12 px).
	CPlotCanvas eq(img, 0, 0, 400, 200, TBox{0, 1000, -30, 30}, true);
	EXPECT_NEAR(eq.px(1000) - eq.px(0), 400, 1e-9);
	EXPECT_NEAR(eq.py(-30) - eq.py(30), 24, 1e-9);
	// y up: larger y is a smaller row.
	EXPECT_LT(fill.py(10), fill.py(0));
	// A segment far outside the area draws nothing and does not crash.
	fill.line(-1e12, 1e12, -1e12, -1e12, mrpt::img::TColor(0, 0, 0));
	fill.ellipse({5000, 0}, Eigen::Matrix2d::Identity(), 3, mrpt::img::TColor(0, 0, 0));
	EXPECT_EQ(countPixels(img, mrpt::img::TColor(0, 0, 0)).second, 0u);
	fill.line(0, 0, 1000, 0, mrpt::img::TColor(0, 0, 0));
	EXPECT_GE(countPixels(img, mrpt::img::TColor(0, 0, 0)).second, 400u);
	const auto t = niceTicks(0, 1000, 5);
	ASSERT_EQ(t.size(), 6u);
	EXPECT_DOUBLE_EQ(t[1], 200);
}

TEST(Figures, EstimatedObjectTracksMoveTheCentroidByXi)
{
	// object 4: features at (0, 0) and (2, 0) (centroid (1, 0)); poses at steps 0, 1 and 3:
	// the track is the centroid moved by xi_xy, broken by a NaN where step 2 is missing
	TRunEstimates est;
	for (const double x : {0.0, 2.0})
	{
		TObjectFeatureEstimate f;
		f.object = 4;
		f.mean = Eigen::Vector2d(x, 0);
		est.object_features.push_back(f);
	}
	for (const int k : {3, 0, 1})  // any order
	{
		TObjectPoseEstimate p;
		p.object = 4;
		p.step = k;
		p.mean = Eigen::Vector3d(k, 0.5 * k, 0);
		p.cov = Eigen::Matrix3d::Identity();
		est.object_poses.push_back(p);
	}
	TObjectPoseEstimate orphan;  // object 9 has no feature estimate: left out
	orphan.object = 9;
	orphan.mean = Eigen::Vector3d::Zero();
	orphan.cov = Eigen::Matrix3d::Identity();
	est.object_poses.push_back(orphan);
	const auto tracks = estimatedObjectTracks(est);
	ASSERT_EQ(tracks.size(), 1u);
	const auto& t = tracks.at(4);
	ASSERT_EQ(t.size(), 4u);
	EXPECT_TRUE(t[0].isApprox(Eigen::Vector2d(1, 0)));
	EXPECT_TRUE(t[1].isApprox(Eigen::Vector2d(2, 0.5)));
	EXPECT_TRUE(std::isnan(t[2].x()));
	EXPECT_TRUE(t[3].isApprox(Eigen::Vector2d(4, 1.5)));
}

/** Issue 30 item 6: with the comparison's filters the `dynamic` path was hidden under
 * `dynamic_classified` (the same path, drawn later with the same width). Three series with the
 * very same estimates: each colour must still show inside the plot area, in the map, the error
 * figure and the gap figure; the legend sits outside the plot area. */
TEST(Figures, EveryFilterStaysVisibleWhenPathsCoincide)
{
	const auto gt = highway();
	const auto a = noisyRun(gt, 4, 0.5);
	const std::vector<TFigureSeries> s = {{"dynamic", seriesColor(1), &a},
	                                      {"dynamic_classified", seriesColor(6), &a},
	                                      {"default", seriesColor(7), &a}};
	auto insidePlot = [](const mrpt::img::CImage& img, const mrpt::img::TColor& c, int right)
	{
		size_t n = 0;
		for (int y = 45; y < static_cast<int>(img.getHeight()) - 60; ++y)
			for (int x = 95; x < static_cast<int>(img.getWidth()) - right; ++x)
			{
				const uint8_t* p = img(x, y);  // BGR
				n += p[2] == c.R && p[1] == c.G && p[0] == c.B;
			}
		return n;
	};
	TMapFigureOptions mo;
	mo.show_landmarks = mo.show_objects = false;
	const auto map = drawMapFigure(&gt, s, mo);
	const auto err = drawEgoErrorFigure(gt, s);
	for (size_t i = 0; i < s.size(); ++i)
	{
		// right: the legend column (its widest label, 18 characters, at 9 px each + 70)
		const size_t inMap = insidePlot(map, s[i].color, 40 + 9 * 18 + 30);
		const size_t inErr = insidePlot(err, s[i].color, 40 + 9 * 18 + 30);
		std::printf("[  info    ] %s: %zu pixels in the map, %zu in the error figure\n",
		            s[i].name.c_str(), inMap, inErr);
		EXPECT_GT(inMap, 500u) << s[i].name;
		EXPECT_GT(inErr, 500u) << s[i].name;
	}
	EXPECT_EQ(seriesStyle(2, 3).dash, 0);  // the last drawn: solid and thinnest
	EXPECT_LT(seriesStyle(2, 3).width, seriesStyle(1, 3).width);
	EXPECT_GT(seriesStyle(1, 3).dash, 0);
}

TEST(Figures, DashedPolylineAndGroupedAgentLegend)
{
	mrpt::img::CImage img(400, 100, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, 399, 99, mrpt::img::TColor(255, 255, 255));
	CPlotCanvas cv(img, 0, 0, 400, 100, TBox{0, 400, 0, 100}, false);
	const mrpt::img::TColor red(255, 0, 0);
	cv.polyline({Eigen::Vector2d(10, 50), Eigen::Vector2d(200, 50), Eigen::Vector2d(310, 50)}, red,
	            1, 12);
	size_t on = 0, dashes = 0;
	bool was = false;
	for (int x = 10; x < 310; ++x)
	{
		const bool red = img(x, 50)[2] == 255 && img(x, 50)[1] == 0;
		on += red;
		dashes += red && !was;
		was = red;
	}
	// 12 on (13 pixels with both ends), 6 off, the pattern running on across the segment joint
	// at x = 200: 300 / 18 = 16.7 dashes, 300 * 13 / 18 = 217 pixels (measured 220).
	EXPECT_GE(dashes, 16u);
	EXPECT_LE(dashes, 18u);
	EXPECT_NEAR(double(on), 217.0, 9.0);

	// 53 agents (KITTI): one legend line for all of them, not 53
	auto gt = highway();
	while (gt.objects.size() < 53) gt.objects.push_back(gt.objects[0]);
	const auto est = noisyRun(highway(), 5, 0.5);
	const auto map = drawMapFigure(&gt, {{"dynamic", seriesColor(1), &est}});
	const int legendBottom = 40 + 6 + 16 * 6 + 8;  // at most 6 lines: agents, truth, filter, marks
	size_t below = 0;
	for (int y = legendBottom + 2; y < 600; ++y)
		for (int x = 1365; x < 1600; ++x) below += map(x, y)[0] != 255;  // right of the plot
	EXPECT_EQ(below, 0u);
}
