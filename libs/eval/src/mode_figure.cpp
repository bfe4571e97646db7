#include <dynslam/eval/figures.h>
#include <dynslam/eval/mode_figure.h>
#include <dynslam/eval/plot_canvas.h>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace dynslam::eval
{
bool hasModeProbabilities(const TRunEstimates& est)
{
	const size_t m = est.object_mode_names.size();
	return m > 0 &&
	       std::any_of(est.object_poses.begin(), est.object_poses.end(),
	                   [m](const auto& p) { return size_t(p.mode_probabilities.size()) == m; });
}

mrpt::img::CImage drawModeFigure(const TRunEstimates& est, const TModeFigureOptions& opt)
{
	if (!hasModeProbabilities(est))
		throw std::invalid_argument("drawModeFigure: the run has no mode probabilities");
	const size_t M = est.object_mode_names.size();
	// object -> mode -> (step, probability), ascending step
	std::map<int32_t, std::vector<std::vector<Eigen::Vector2d>>> lines;
	double s0 = 1e300, s1 = -1e300;
	for (const auto& p : est.object_poses)
	{
		if (size_t(p.mode_probabilities.size()) != M) continue;
		auto& l = lines[p.object];
		if (l.empty()) l.resize(M);
		for (size_t j = 0; j < M; ++j)
			l[j].emplace_back(p.step, p.mode_probabilities[Eigen::Index(j)]);
		s0 = std::min(s0, double(p.step));
		s1 = std::max(s1, double(p.step));
	}
	const size_t n = std::min(lines.size(), opt.max_objects);
	std::vector<TLegendEntry> legend;
	for (size_t j = 0; j < M; ++j)
		legend.push_back({est.object_mode_names[j], seriesColor(j), 0, 2, 0});
	const int left = 80, right = legendWidth(legend) + 30, top = 40, gap = 45, bottom = 15;
	const int height = top + int(n) * (opt.panel_height + gap) + bottom;
	mrpt::img::CImage img(opt.width, height, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, opt.width - 1, height - 1, mrpt::img::TColor(255, 255, 255));
	const TBox world{s0, std::max(s1, s0 + 1), -0.02, 1.02};
	size_t k = 0;
	for (auto& [obj, l] : lines)
	{
		if (k == n) break;
		const int y = top + int(k) * (opt.panel_height + gap);
		CPlotCanvas cv(img, left, y, opt.width - left - right, opt.panel_height, world, false);
		const std::string title =
		    (k == 0 ? opt.title + ": " : std::string()) + "object " + std::to_string(obj);
		cv.axes(k + 1 == n ? "step" : "", "P(mode)", title);
		for (size_t j = 0; j < M; ++j)
		{
			std::sort(l[j].begin(), l[j].end(),
			          [](const auto& a, const auto& b) { return a[0] < b[0]; });
			cv.polyline(l[j], seriesColor(j), 2);
		}
		if (k == 0) cv.legend(legend, true);
		++k;
	}
	return img;
}
}  // namespace dynslam::eval
