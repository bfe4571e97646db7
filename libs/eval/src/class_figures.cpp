/** Classification figures (class_figures.h). */
#include <dynslam/eval/class_figures.h>
#include <dynslam/eval/figures.h>
#include <dynslam/eval/plot_canvas.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace dynslam::eval
{
using mrpt::img::TColor;

namespace
{
const TColor kStatic(30, 80, 220), kMoving(220, 30, 30), kUndecided(170, 170, 170),
    kWrong(240, 140, 0), kClutter(0, 0, 0), kTruthGrey(185, 185, 185), kBackground(255, 255, 255);

/** The true class of each written ID: moving if any reading of it is moving, clutter if all
 * are clutter, else static. */
std::map<int32_t, io::TrueClass> trueClassOfIds(const std::vector<io::TReadingClass>& truth)
{
	std::map<int32_t, io::TrueClass> c;
	for (const auto& r : truth)
	{
		if (r.id < 0) continue;
		auto [it, added] = c.emplace(r.id, r.cls);
		if (!added && r.cls == io::TrueClass::Moving) it->second = io::TrueClass::Moving;
		if (!added && it->second == io::TrueClass::Clutter && r.cls == io::TrueClass::Static)
			it->second = io::TrueClass::Static;
	}
	return c;
}
}  // namespace

mrpt::img::CImage drawClassMap(const io::TGroundTruth* gt, const TRunEstimates& est,
                               const std::vector<io::TReadingClass>& truth,
                               const std::string& title, int width, int height)
{
	if (width < 200 || height < 150)
		throw std::invalid_argument("drawClassMap: figure size must be at least 200 x 150 pixels");
	mrpt::img::CImage img(width, height, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, width - 1, height - 1, kBackground);
	TBox box = TBox::empty();
	for (const auto& e : est.ego) box.expand(e.mean[0], e.mean[1]);
	for (const auto& l : est.landmarks) box.expand(l.mean[0], l.mean[1]);
	if (gt)
	{
		for (const auto& e : gt->ego) box.expand(e[0], e[1]);
		for (const auto& [id, p] : gt->landmarks) box.expand(p[0], p[1]);
	}
	if (!box.valid()) box = TBox();
	CPlotCanvas cv(img, 80, 40, width - 110, height - 100, box.withMargin(0.03), false);
	cv.axes("x [m]", "y [m]", title);
	std::vector<TLegendEntry> legend;
	if (gt)
	{
		std::vector<Eigen::Vector2d> path;
		for (const auto& e : gt->ego) path.push_back(e.head<2>());
		cv.polyline(path, kTruthGrey, 2);
		for (const auto& [id, p] : gt->landmarks) cv.mark(p[0], p[1], kTruthGrey, 'x', 3);
		legend.push_back({"ego and landmarks (truth)", kTruthGrey, 0});
	}
	std::map<int, Eigen::Vector3d> ego;
	for (const auto& e : est.ego) ego[e.step] = e.mean;
	std::vector<Eigen::Vector2d> path;
	for (const auto& [k, m] : ego) path.push_back(m.head<2>());
	cv.polyline(path, TColor(0, 0, 0), 2);
	legend.push_back({"ego (estimate)", TColor(0, 0, 0), 0});
	// Moving: the estimated object tracks (centroid of f_0 moved by xi), f_0 marked.
	for (const auto& f : est.object_features) cv.mark(f.mean[0], f.mean[1], kMoving, 'x', 3);
	for (const auto& [o, track] : estimatedObjectTracks(est)) cv.polyline(track, kMoving, 1);
	if (!est.object_features.empty()) legend.push_back({"decided moving (objects)", kMoving, 'x'});
	// Static: the final map, orange where the truth says the track moves (or is clutter).
	const auto cls = trueClassOfIds(truth);
	size_t wrong = 0;
	for (const auto& l : est.landmarks)
	{
		const auto it = cls.find(l.id);
		const bool bad = it != cls.end() && it->second != io::TrueClass::Static;
		wrong += bad;
		cv.mark(l.mean[0], l.mean[1], bad ? kWrong : kStatic, 's', bad ? 4 : 3);
	}
	legend.push_back({"decided static (final map)", kStatic, 's'});
	if (!truth.empty())
		legend.push_back({"static, truly moving/clutter: " + std::to_string(wrong), kWrong, 's'});
	cv.legend(legend);
	return img;
}

mrpt::img::CImage drawDecisionTimeline(const TReadingDecisions& d,
                                       const std::vector<io::TReadingClass>& truth,
                                       const std::string& title, int max_rows)
{
	if (d.steps.size() != d.ids.size() || d.ids.size() != d.decisions.size())
		throw std::invalid_argument(
		    "drawDecisionTimeline: steps, ids and decisions differ in size");
	const bool withTruth = truth.size() == d.ids.size();
	// Rows: the tracks, by true class (static, moving, clutter) then first step.
	std::map<int32_t, std::pair<int, int>> key;  // id -> (class rank, first step)
	int lastStep = 0;
	for (size_t i = 0; i < d.ids.size(); ++i)
	{
		lastStep = std::max(lastStep, d.steps[i]);
		if (d.ids[i] < 0) continue;
		const int rank = withTruth ? int(truth[i].cls) : 0;
		auto [it, added] = key.emplace(d.ids[i], std::make_pair(rank, d.steps[i]));
		if (!added) it->second.first = std::max(it->second.first, rank);
	}
	std::vector<std::pair<std::pair<int, int>, int32_t>> order;
	for (const auto& [id, k] : key) order.push_back({k, id});
	std::sort(order.begin(), order.end());
	const size_t rows = std::min(order.size(), size_t(std::max(1, max_rows)));
	std::map<int32_t, size_t> rowOf;
	for (size_t r = 0; r < rows; ++r) rowOf[order[r].second] = r;
	const int rowH = std::clamp(600 / int(std::max<size_t>(rows, 1)), 4, 14);
	const int left = 80, top = 40, plotW = 1200, plotH = int(rows) * rowH;
	const int width = left + plotW + 30, height = std::max(200, top + plotH + 60);
	mrpt::img::CImage img(width, height, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, width - 1, height - 1, kBackground);
	TBox box{-0.5, double(lastStep) + 0.5, 0, double(std::max<size_t>(rows, 1))};
	CPlotCanvas cv(img, left, top, plotW, std::max(plotH, 100), box, false);
	std::string t = title + " (" + std::to_string(rows) + " of " + std::to_string(order.size()) +
	                " tracks; upper: decision" + (withTruth ? ", lower: truth)" : ")");
	cv.axes("step", "track", t);
	const double xw = 0.5;  // [steps] width of one reading's mark
	for (size_t i = 0; i < d.ids.size(); ++i)
	{
		const auto it = rowOf.find(d.ids[i]);
		if (it == rowOf.end()) continue;
		const double y = double(rows - 1 - it->second);  // first row on top
		const double x = d.steps[i];
		const TColor c = d.decisions[i] == Decision::Static   ? kStatic
		                 : d.decisions[i] == Decision::Moving ? kMoving
		                                                      : kUndecided;
		const double ytop = withTruth ? y + 0.45 : y + 0.1;
		for (double yy = ytop; yy < y + 0.9; yy += 0.1)
			cv.line(x - xw / 2, yy, x + xw / 2, yy, c, 1);
		if (withTruth)
		{
			const TColor tc = truth[i].cls == io::TrueClass::Static   ? kStatic
			                  : truth[i].cls == io::TrueClass::Moving ? kMoving
			                                                          : kClutter;
			for (double yy = y + 0.1; yy < y + 0.4; yy += 0.1)
				cv.line(x - xw / 2, yy, x + xw / 2, yy, tc, 1);
		}
	}
	cv.legend({{"undecided", kUndecided, 's'}, {"static", kStatic, 's'}, {"moving", kMoving, 's'}});
	return img;
}
}  // namespace dynslam::eval
