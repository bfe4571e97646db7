#include <dynslam/eval/gap_figure.h>
#include <dynslam/eval/plot_canvas.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace dynslam::eval
{
namespace
{
/** Per series: (true ego x, position error) by step, for the steps in the ground truth. */
std::vector<Eigen::Vector2d> errorOverRoad(const io::TGroundTruth& gt, const TRunEstimates& est)
{
	std::map<int, Eigen::Vector2d> byStep;
	for (const TEgoEstimate& e : est.ego)
	{
		if (e.step < 0 || size_t(e.step) >= gt.numSteps()) continue;
		const Eigen::Vector3d& t = gt.ego[size_t(e.step)];
		byStep[e.step] = Eigen::Vector2d(t.x(), (e.mean.head<2>() - t.head<2>()).norm());
	}
	std::vector<Eigen::Vector2d> out;
	for (const auto& [k, p] : byStep) out.push_back(p);
	return out;
}
}  // namespace

mrpt::img::CImage drawGapErrorFigure(const io::TGroundTruth& gt,
                                     const std::vector<TFigureSeries>& series,
                                     const std::vector<std::pair<double, double>>& gaps, int width,
                                     int height)
{
	mrpt::img::CImage img(width, height, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, width - 1, height - 1, mrpt::img::TColor(255, 255, 255));
	std::vector<std::vector<Eigen::Vector2d>> lines;
	TBox box = TBox::empty();
	for (const auto& s : series)
	{
		lines.push_back(s.est ? errorOverRoad(gt, *s.est) : std::vector<Eigen::Vector2d>{});
		for (const auto& p : lines.back()) box.expand(p[0], p[1]);
	}
	box.expand(box.xmin, 0.0);
	TBox w = box.withMargin(0.02);
	w.ymin = 0;
	w.ymax = 1.1 * box.ymax;
	if (!w.valid()) w = TBox{0, 1, 0, 1};
	const mrpt::img::TColor shade(235, 230, 205);  // not the grid's grey
	std::vector<TLegendEntry> legend;
	for (size_t i = 0; i < series.size(); ++i)
	{
		const TSeriesStyle st = seriesStyle(i, series.size());
		legend.push_back({series[i].name, series[i].color, 0, st.width, st.dash});
	}
	if (!gaps.empty()) legend.push_back({"landmark gap", shade, 's'});
	const int left = 80, right = legendWidth(legend) + 20, top = 40, bottom = 55;
	if (width - left - right < 100)
		throw std::invalid_argument("gap figure: too narrow for its legend");
	CPlotCanvas cv(img, left, top, width - left - right, height - top - bottom, w, false);
	for (const auto& [a, b] : gaps)  // shaded first, under the axes and the lines
	{
		const double x0 = std::max(a, w.xmin), x1 = std::min(b, w.xmax);
		if (x1 > x0)
			img.filledRectangle(int(cv.px(x0)), top, int(cv.px(x1)), height - bottom - 1, shade);
	}
	cv.axes("true ego x along the road [m]", "ego position error [m]",
	        "Ego position error over the road (landmark gaps shaded)");
	for (size_t i = 0; i < series.size(); ++i)
	{
		const TSeriesStyle st = seriesStyle(i, series.size());
		cv.polyline(lines[i], series[i].color, st.width, st.dash);
	}
	cv.legend(legend, true);
	return img;
}
}  // namespace dynslam::eval
