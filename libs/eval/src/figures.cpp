#include "dynslam/eval/figures.h"

#include <dynslam/eval/metrics.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

namespace dynslam::eval
{
using mrpt::img::TColor;

TColor seriesColor(size_t i)
{
	static const TColor palette[] = {TColor(220, 30, 30), TColor(30, 80, 220),  TColor(20, 150, 40),
	                                 TColor(240, 140, 0), TColor(150, 40, 180), TColor(0, 170, 170),
	                                 TColor(140, 90, 40), TColor(230, 60, 160)};
	return palette[i % (sizeof(palette) / sizeof(palette[0]))];
}

TSeriesStyle seriesStyle(size_t i, size_t n)
{
	const int fromLast = n > i ? static_cast<int>(n - 1 - i) : 0;
	return {std::min(8, 2 + 2 * fromLast), fromLast % 2 == 1 ? 14 : 0};
}

namespace
{
const TColor kBlack(0, 0, 0), kGrey(150, 150, 150), kWhite(255, 255, 255);

TColor objectColor(size_t i)
{
	static const TColor palette[] = {TColor(60, 170, 60), TColor(70, 110, 230),
	                                 TColor(170, 70, 200), TColor(200, 150, 30)};
	return palette[i % 4];
}

mrpt::img::CImage blankImage(int w, int h)
{
	if (w < 200 || h < 150)
		throw std::invalid_argument("figure size must be at least 200 x 150 pixels");
	mrpt::img::CImage img(w, h, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, w - 1, h - 1, kWhite);
	return img;
}

/// Ground-truth centroid of an object's features per step (NaN where undefined).
std::vector<Eigen::Vector2d> truthCentroids(const io::TObjectGroundTruth& o)
{
	std::vector<Eigen::Vector2d> c;
	for (const auto& f : o.features)
		c.push_back(f.cols() > 0 ? Eigen::Vector2d(f.rowwise().mean())
		                         : Eigen::Vector2d::Constant(kNaN));
	return c;
}

std::vector<Eigen::Vector2d> egoPath(const std::vector<TEgoEstimate>& ego)
{
	std::vector<const TEgoEstimate*> v;
	for (const auto& e : ego) v.push_back(&e);
	std::sort(v.begin(), v.end(), [](auto a, auto b) { return a->step < b->step; });
	std::vector<Eigen::Vector2d> p;
	for (const auto* e : v) p.push_back(e->mean.head<2>());
	return p;
}
/** The map's legend: agents (grouped beyond kMaxAgentLegendEntries), truth, every series in
 * its line style, and the estimate markers if any are drawn. */
std::vector<TLegendEntry> mapLegend(const io::TGroundTruth* gt,
                                    const std::vector<TFigureSeries>& series,
                                    const TMapFigureOptions& opt)
{
	std::vector<TLegendEntry> legend;
	if (gt && opt.show_objects && !gt->objects.empty())
	{
		if (gt->objects.size() > kMaxAgentLegendEntries)
			legend.push_back({"agents 1-" + std::to_string(gt->objects.size()) + " (truth)",
			                  lighter(objectColor(0), 0.35), 0});
		else
			for (size_t i = 0; i < gt->objects.size(); ++i)
				legend.push_back({"agent " + std::to_string(i + 1) + " (object " +
				                      std::to_string(gt->objects[i].object) + ", truth)",
				                  lighter(objectColor(i), 0.35), 0});
	}
	if (gt && opt.show_landmarks && !gt->landmarks.empty())
		legend.push_back({"landmarks (truth)", kBlack, 'x'});
	if (gt) legend.push_back({"ego (truth)", kBlack, 0});
	bool landmarks = false, tracks = false;
	for (size_t i = 0; i < series.size(); ++i)
	{
		if (!series[i].est) continue;
		const TSeriesStyle st = seriesStyle(i, series.size());
		legend.push_back({series[i].name, series[i].color, 0, st.width, st.dash});
		landmarks = landmarks || !series[i].est->landmarks.empty();
		tracks = tracks || !series[i].est->object_poses.empty();
	}
	if (opt.show_landmarks && landmarks) legend.push_back({"landmark estimates", kGrey, 's'});
	if (opt.show_objects && tracks) legend.push_back({"object estimates", kGrey, '.'});
	return legend;
}
}  // namespace

mrpt::img::CImage drawMapFigure(const io::TGroundTruth* gt,
                                const std::vector<TFigureSeries>& series,
                                const TMapFigureOptions& opt)
{
	auto img = blankImage(opt.width, opt.height);
	// World box: everything that will be drawn.
	TBox box = TBox::empty();
	if (gt)
	{
		for (const auto& e : gt->ego) box.expand(e[0], e[1]);
		if (opt.show_landmarks)
			for (const auto& [id, p] : gt->landmarks) box.expand(p[0], p[1]);
		if (opt.show_objects)
			for (const auto& o : gt->objects)
				for (const auto& c : truthCentroids(o)) box.expand(c[0], c[1]);
	}
	for (const auto& s : series)
	{
		if (!s.est) continue;
		for (const auto& e : s.est->ego) box.expand(e.mean[0], e.mean[1]);
		if (opt.show_landmarks)
			for (const auto& l : s.est->landmarks) box.expand(l.mean[0], l.mean[1]);
	}
	const TBox world = opt.view ? *opt.view : box.withMargin(0.03);
	const auto legend = mapLegend(gt, series, opt);

	const int left = 80, top = 40, right = legendWidth(legend) + 20, bottom = 55;
	if (opt.width - left - right < 100)
		throw std::invalid_argument("map figure: too narrow for its legend");
	CPlotCanvas cv(img, left, top, opt.width - left - right, opt.height - top - bottom, world,
	               opt.equal_aspect);
	cv.axes("x [m]", "y [m]",
	        opt.title + (opt.equal_aspect ? "" : "  (x and y scaled differently)"));

	if (gt)
	{
		if (opt.show_objects)
			for (size_t i = 0; i < gt->objects.size(); ++i)
			{
				const auto& o = gt->objects[i];
				const auto c = truthCentroids(o);
				cv.polyline(c, lighter(objectColor(i), 0.35), 2);
				if (o.first_step >= 0 && static_cast<size_t>(o.first_step) < o.features.size())
					for (int k = 0; k < o.features[o.first_step].cols(); ++k)
						cv.mark(o.features[o.first_step](0, k), o.features[o.first_step](1, k),
						        objectColor(i), '+', 4);
			}
		if (opt.show_landmarks)
			for (const auto& [id, p] : gt->landmarks) cv.mark(p[0], p[1], kBlack, 'x', 3);
		std::vector<Eigen::Vector2d> path;
		for (const auto& e : gt->ego) path.push_back(e.head<2>());
		cv.polyline(path, kBlack, 2);
	}
	for (size_t si = 0; si < series.size(); ++si)
	{
		const auto& s = series[si];
		if (!s.est) continue;
		if (opt.show_landmarks)
			for (const auto& l : s.est->landmarks)
			{
				if (opt.show_ellipses) cv.ellipse(l.mean, l.cov, opt.sigma, lighter(s.color, 0.3));
				cv.mark(l.mean[0], l.mean[1], s.color, 's', 2);
			}
		if (opt.show_objects)
			for (const auto& [o, track] : estimatedObjectTracks(*s.est))
			{
				cv.polyline(track, s.color, 1);
				for (const auto& p : track) cv.mark(p[0], p[1], s.color, '.');
			}
		const TSeriesStyle st = seriesStyle(si, series.size());
		cv.polyline(egoPath(s.est->ego), s.color, st.width, st.dash);
	}
	cv.legend(legend, true);
	return img;
}

mrpt::img::CImage drawEgoErrorFigure(const io::TGroundTruth& gt,
                                     const std::vector<TFigureSeries>& series,
                                     const TErrorFigureOptions& opt)
{
	auto img = blankImage(opt.width, opt.height);
	std::vector<std::vector<TEgoErrorRow>> rows;
	for (const auto& s : series)
		rows.push_back(s.est ? egoErrors(gt, s.est->ego) : std::vector<TEgoErrorRow>{});
	// Time axis from the first stamp: stamps are the rawlog's (e.g. 1.6e9 s since 1970).
	double t0 = std::numeric_limits<double>::infinity();
	for (const auto& v : rows)
		for (const auto& r : v)
			if (std::isfinite(r.t)) t0 = std::min(t0, r.t);
	auto xOf = [&](const TEgoErrorRow& r)
	{ return opt.time_axis && std::isfinite(r.t) ? r.t - t0 : static_cast<double>(r.step); };
	TBox xr = TBox::empty();
	for (const auto& v : rows)
		for (const auto& r : v) xr.expand(xOf(r), 0);
	static const char* names[3] = {"x error [m]", "y error [m]", "theta error [rad]"};
	std::vector<TLegendEntry> legend;
	for (size_t s = 0; s < series.size(); ++s)
	{
		const TSeriesStyle st = seriesStyle(s, series.size());
		legend.push_back({series[s].name, series[s].color, 0, st.width, st.dash});
	}
	char sigmaLabel[48];
	std::snprintf(sigmaLabel, sizeof(sigmaLabel), "+-%g sigma (light)", opt.sigma);
	legend.push_back({sigmaLabel, lighter(kBlack), 0, 1});
	const int left = 90, right = legendWidth(legend) + 20, top = 40, gap = 60, bottom = 55;
	if (opt.width - left - right < 100)
		throw std::invalid_argument("error figure: too narrow for its legend");
	const int panelH = (opt.height - top - bottom - 2 * gap) / 3;
	for (int i = 0; i < 3; ++i)
	{
		double ymax = 0;
		for (const auto& v : rows)
			for (const auto& r : v)
				ymax = std::max({ymax, std::abs(r.error[i]), opt.sigma / 3.0 * r.sigma3[i]});
		if (!(ymax > 0) || !std::isfinite(ymax)) ymax = 1;
		TBox w{xr.xmin, xr.xmax, -1.1 * ymax, 1.1 * ymax};
		if (!(w.xmax > w.xmin)) w = w.withMargin(0);
		CPlotCanvas cv(img, left, top + i * (panelH + gap), opt.width - left - right, panelH, w,
		               false);
		cv.axes(i == 2 ? (opt.time_axis ? "time since the first step [s]" : "step") : "", names[i],
		        i == 0 ? opt.title : "");
		cv.line(w.xmin, 0, w.xmax, 0, kGrey);
		for (size_t s = 0; s < rows.size(); ++s)
		{
			std::vector<Eigen::Vector2d> e, up, lo;
			for (const auto& r : rows[s])
			{
				const double b = opt.sigma / 3.0 * r.sigma3[i];
				e.emplace_back(xOf(r), r.error[i]);
				up.emplace_back(xOf(r), b);
				lo.emplace_back(xOf(r), -b);
			}
			const TColor c = series[s].color;
			cv.polyline(up, lighter(c), 1);
			cv.polyline(lo, lighter(c), 1);
			const TSeriesStyle st = seriesStyle(s, series.size());
			cv.polyline(e, c, st.width, st.dash);
		}
		if (i == 0) cv.legend(legend, true);
	}
	return img;
}

mrpt::img::CImage drawConsistencyFigure(const TConsistencyStats& stats,
                                        const TConsistencyFigureOptions& opt)
{
	auto img = blankImage(opt.width, opt.height);
	TBox box = TBox::empty();
	double maxUpper = 0;
	for (const auto& r : stats.rows)
	{
		box.expand(r.key, r.mean);
		box.expand(r.key, r.upper);
		box.expand(r.key, 0.0);
		maxUpper = std::max(maxUpper, r.upper);
	}
	TBox w = box.withMargin(0.02);
	if (maxUpper > 0) w.ymax = std::min(w.ymax, 3.0 * maxUpper);
	w.ymin = 0;
	if (!w.valid()) w = TBox{0, 1, 0, 1};
	const int left = 80, right = 20, top = 40, bottom = 55;
	CPlotCanvas cv(img, left, top, opt.width - left - right, opt.height - top - bottom, w, false);
	char title[160];
	std::snprintf(title, sizeof(title), "%s: ANEES %.3f in [%.3f, %.3f], %.1f%% inside",
	              opt.title.empty() ? stats.name.c_str() : opt.title.c_str(), stats.anees,
	              stats.anees_lower, stats.anees_upper, 100.0 * stats.fraction_inside);
	cv.axes(opt.xlabel, "average NEES / NIS", title);
	std::vector<Eigen::Vector2d> m, lo, up;
	for (const auto& r : stats.rows)
	{
		m.emplace_back(r.key, std::min(r.mean, w.ymax));
		lo.emplace_back(r.key, r.lower);
		up.emplace_back(r.key, r.upper);
	}
	cv.polyline(lo, kGrey, 1);
	cv.polyline(up, kGrey, 1);
	cv.polyline(m, seriesColor(1), 2);
	for (const auto& p : m) cv.mark(p[0], p[1], seriesColor(1), '.');
	char band[64];
	std::snprintf(band, sizeof(band), "%g%% chi2 bounds", 100.0 * stats.confidence);
	cv.legend({{stats.name, seriesColor(1), 0}, {band, kGrey, 0}});
	return img;
}

void savePng(const mrpt::img::CImage& img, const std::string& path)
{
	if (!img.saveToFile(path)) throw std::runtime_error("cannot write image '" + path + "'");
}

std::map<int32_t, std::vector<Eigen::Vector2d>> estimatedObjectTracks(const TRunEstimates& est)
{
	std::map<int32_t, Eigen::Vector2d> sum;
	std::map<int32_t, int> n;
	for (const auto& f : est.object_features)
	{
		sum.try_emplace(f.object, Eigen::Vector2d::Zero());
		sum[f.object] += f.mean;
		++n[f.object];
	}
	std::map<int32_t, std::vector<std::pair<int, Eigen::Vector2d>>> byStep;
	for (const auto& p : est.object_poses)
		if (n.count(p.object))
			byStep[p.object].emplace_back(p.step, sum[p.object] / n[p.object] + p.mean.head<2>());
	std::map<int32_t, std::vector<Eigen::Vector2d>> tracks;
	for (auto& [o, v] : byStep)
	{
		std::sort(v.begin(), v.end(),
		          [](const auto& a, const auto& b) { return a.first < b.first; });
		int last = -2;
		for (const auto& [step, p] : v)
		{
			if (step != last + 1 && !tracks[o].empty())
				tracks[o].push_back(Eigen::Vector2d::Constant(kNaN));  // break a gap
			tracks[o].push_back(p);
			last = step;
		}
	}
	return tracks;
}
}  // namespace dynslam::eval
