#include <dynslam/sim/figure.h>
#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace dynslam::sim
{
namespace
{
using mrpt::img::TColor;

/** World -> pixel with independent x and y scales (y up). */
struct TView
{
	double x0 = 0, y0 = 0, sx = 1, sy = 1;
	int H = 0;
	int px(double x) const { return int(std::lround((x - x0) * sx)); }
	int py(double y) const { return H - int(std::lround((y - y0) * sy)); }
};

TColor objectColor(size_t i)
{
	static const TColor c[] = {TColor(0, 160, 0),   TColor(0, 70, 230),  TColor(150, 0, 170),
	                           TColor(0, 160, 160), TColor(200, 110, 0), TColor(120, 120, 0)};
	return c[i % (sizeof(c) / sizeof(c[0]))];
}

/** Bounding box of everything drawn (the road too on the highway). */
void boundingBox(const io::TGroundTruth& gt, const TScenarioOptions& o, double& xmin, double& xmax,
                 double& ymin, double& ymax)
{
	xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
	auto grow = [&](double x, double y)
	{
		xmin = std::min(xmin, x), xmax = std::max(xmax, x);
		ymin = std::min(ymin, y), ymax = std::max(ymax, y);
	};
	for (const auto& x : gt.ego) grow(x[0], x[1]);
	for (const auto& [id, p] : gt.landmarks) grow(p[0], p[1]);
	for (const auto& og : gt.objects)
		for (const auto& F : og.features)
			for (Eigen::Index j = 0; j < F.cols(); ++j) grow(F(0, j), F(1, j));
	if (o.type == ScenarioType::Highway)
	{
		grow(0, o.highway.roadRight());
		grow(o.highway.length, o.highway.roadLeft());
	}
}

/** View of the scene in a W x H image with margins; crops W and H to the drawing. */
TView fitView(const io::TGroundTruth& gt, const TScenarioOptions& o, int& W, int& H)
{
	double xmin, xmax, ymin, ymax;
	boundingBox(gt, o, xmin, xmax, ymin, ymax);
	const int mL = 40, mR = 20, mT = 60, mB = 30;
	const double bw = std::max(xmax - xmin, 1.0), bh = std::max(ymax - ymin, 1.0);
	TView v;
	v.sx = (W - mL - mR) / bw;
	v.sy = (H - mT - mB) / bh;
	// Equal scales unless the scene is much longer than wide (the highway).
	const double stretch = v.sy / v.sx;
	if (stretch < 1.0) v.sx = v.sy;
	if (stretch >= 1.0 && stretch < 3.0) v.sy = v.sx;
	// Crop the unused width or height of an equal-scale drawing (keep room for the legend).
	W = std::max(std::min(W, int(std::ceil(bw * v.sx)) + mL + mR), 1000);
	H = std::min(H, int(std::ceil(bh * v.sy)) + mT + mB);
	v.x0 = xmin - mL / v.sx;
	v.y0 = ymin - mB / v.sy;
	v.H = H;
	return v;
}

void drawRoad(mrpt::img::CImage& img, const TView& v, const THighwayOptions& h)
{
	img.filledRectangle(v.px(0), v.py(h.roadLeft()), v.px(h.length), v.py(h.roadRight()),
	                    TColor(225, 225, 225));
	for (double y : {h.roadLeft(), h.roadRight()})
		img.line(v.px(0), v.py(y), v.px(h.length), v.py(y), TColor(90, 90, 90), 2);
	for (int l = 1; l < h.num_lanes; ++l)
	{
		const double y = h.roadRight() + l * h.lane_width;
		img.line(v.px(0), v.py(y), v.px(h.length), v.py(y), TColor(150, 150, 150), 1,
		         mrpt::img::CCanvas::psDash);
	}
}

void drawPolyline(mrpt::img::CImage& img, const TView& v, const std::vector<Eigen::Vector2d>& pts,
                  TColor c, int w)
{
	for (size_t k = 1; k < pts.size(); ++k)
		img.line(v.px(pts[k - 1][0]), v.py(pts[k - 1][1]), v.px(pts[k][0]), v.py(pts[k][1]), c, w);
}

/** Landmarks, object tracks (centre path, features at first sighting, start mark), ego path. */
void drawScene(mrpt::img::CImage& img, const TView& v, const io::TGroundTruth& gt)
{
	for (const auto& [id, p] : gt.landmarks)
	{
		const int x = v.px(p[0]), y = v.py(p[1]);
		img.filledRectangle(x - 3, y - 3, x + 3, y + 3, TColor(250, 210, 0));
		img.rectangle(x - 3, y - 3, x + 3, y + 3, TColor(120, 100, 0));
	}
	for (size_t i = 0; i < gt.objects.size(); ++i)
	{
		const auto& og = gt.objects[i];
		const TColor c = objectColor(i);
		std::vector<Eigen::Vector2d> centre;
		for (const auto& F : og.features) centre.push_back(F.rowwise().mean());
		drawPolyline(img, v, centre, c, 2);
		// Features at the first sighting (the filter's time 0).
		if (og.first_step >= 0)
		{
			const auto& F = og.features[og.first_step];
			for (Eigen::Index j = 0; j < F.cols(); ++j)
				img.drawMark(v.px(F(0, j)), v.py(F(1, j)), c, 's', 4, 2);
		}
		img.drawMark(v.px(centre.front()[0]), v.py(centre.front()[1]), c, '+', 6, 2);
	}
	std::vector<Eigen::Vector2d> ego;
	for (const auto& x : gt.ego) ego.push_back(x.head<2>());
	drawPolyline(img, v, ego, TColor(220, 0, 0), 3);
	img.drawMark(v.px(0), v.py(0), TColor(220, 0, 0), '+', 8, 2);
}

/** Title line, colour legend and the axis scales. */
void drawLegend(mrpt::img::CImage& img, const TView& v, const io::TGroundTruth& gt,
                const TScenarioOptions& o, int H)
{
	const bool highway = o.type == ScenarioType::Highway;
	char buf[200];
	std::snprintf(
	    buf, sizeof(buf),
	    "%s: %zu steps of %.2f s, %zu static landmarks, %zu moving objects, sensor range %.0f m",
	    o.name.c_str(), gt.numSteps(), o.dt, gt.landmarks.size(), gt.objects.size(),
	    o.sensor_range);
	img.textOut(10, 8, buf, TColor(0, 0, 0));
	int lx = 10;
	auto legend = [&](const std::string& s, TColor c)
	{
		img.filledRectangle(lx, 32, lx + 14, 44, c);
		img.textOut(lx + 20, 30, s, TColor(0, 0, 0));
		lx += 30 + int(s.size()) * 9;
	};
	legend("ego", TColor(220, 0, 0));
	for (size_t i = 0; i < gt.objects.size() && i < 6; ++i)
		legend(highway && i < o.highway.agents.size()
		           ? "Agent " + std::to_string(i + 1) + " (object " + std::to_string(i) + ")"
		           : "object " + std::to_string(i),
		       objectColor(i));
	legend("static landmarks", TColor(250, 210, 0));
	std::snprintf(buf, sizeof(buf), "x: %.0f m per 100 px   y: %.1f m per 100 px%s", 100 / v.sx,
	              100 / v.sy, v.sy > v.sx * 1.01 ? "  (lateral axis stretched)" : "");
	img.textOut(10, H - 18, buf, TColor(60, 60, 60));
}
}  // namespace

void drawScenarioFigure(const io::TGroundTruth& gt, const TScenarioOptions& o,
                        const std::string& pngPath, int W, int H)
{
	gt.checkConsistent();
	const TView v = fitView(gt, o, W, H);
	mrpt::img::CImage img(W, H, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, W - 1, H - 1, TColor(255, 255, 255));
	img.selectTextFont("9x15");
	if (o.type == ScenarioType::Highway) drawRoad(img, v, o.highway);
	drawScene(img, v, gt);
	drawLegend(img, v, gt, o, H);
	if (!img.saveToFile(pngPath))
		throw std::runtime_error("drawScenarioFigure: cannot write " + pngPath);
}
}  // namespace dynslam::sim
