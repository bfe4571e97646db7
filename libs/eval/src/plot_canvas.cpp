#include "dynslam/eval/plot_canvas.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace dynslam::eval
{
using mrpt::img::TColor;

void TBox::expand(double x, double y)
{
	if (!std::isfinite(x) || !std::isfinite(y)) return;
	xmin = std::min(xmin, x);
	xmax = std::max(xmax, x);
	ymin = std::min(ymin, y);
	ymax = std::max(ymax, y);
}

TBox TBox::empty()
{
	const double inf = std::numeric_limits<double>::infinity();
	return {inf, -inf, inf, -inf};
}

TBox TBox::withMargin(double fraction) const
{
	auto grow = [fraction](double& lo, double& hi)
	{
		if (!(hi >= lo))
		{
			lo = 0;
			hi = 1;
			return;
		}
		double d = hi - lo;
		if (d <= 0)
		{
			const double h = std::max(0.5, 0.1 * std::abs(lo));
			lo -= h;
			hi += h;
			return;
		}
		lo -= fraction * d;
		hi += fraction * d;
	};
	TBox b = *this;
	grow(b.xmin, b.xmax);
	grow(b.ymin, b.ymax);
	return b;
}

CPlotCanvas::CPlotCanvas(mrpt::img::CImage& img, int left, int top, int width, int height,
                         const TBox& world, bool equal_aspect)
    : m_img(img), m_left(left), m_top(top), m_width(width), m_height(height), m_world(world)
{
	if (!m_world.valid()) m_world = m_world.withMargin(0.0);
	m_sx = m_width / (m_world.xmax - m_world.xmin);
	m_sy = m_height / (m_world.ymax - m_world.ymin);
	if (equal_aspect)
	{
		const double s = std::min(m_sx, m_sy);
		const double cx = 0.5 * (m_world.xmin + m_world.xmax);
		const double cy = 0.5 * (m_world.ymin + m_world.ymax);
		const double hx = 0.5 * m_width / s, hy = 0.5 * m_height / s;
		m_world = {cx - hx, cx + hx, cy - hy, cy + hy};
		m_sx = m_sy = s;
	}
}

double CPlotCanvas::px(double x) const { return m_left + (x - m_world.xmin) * m_sx; }
double CPlotCanvas::py(double y) const { return m_top + m_height - (y - m_world.ymin) * m_sy; }

namespace
{
/// Liang-Barsky clipping of a pixel segment to [x0, x1] x [y0, y1]; false if outside.
bool clip(double& ax, double& ay, double& bx, double& by, double x0, double y0, double x1,
          double y1)
{
	double t0 = 0, t1 = 1;
	const double dx = bx - ax, dy = by - ay;
	const double p[4] = {-dx, dx, -dy, dy};
	const double q[4] = {ax - x0, x1 - ax, ay - y0, y1 - ay};
	for (int i = 0; i < 4; ++i)
	{
		if (p[i] == 0)
		{
			if (q[i] < 0) return false;
			continue;
		}
		const double r = q[i] / p[i];
		if (p[i] < 0)
			t0 = std::max(t0, r);
		else
			t1 = std::min(t1, r);
		if (t0 > t1) return false;
	}
	const double nax = ax + t0 * dx, nay = ay + t0 * dy;
	bx = ax + t1 * dx;
	by = ay + t1 * dy;
	ax = nax;
	ay = nay;
	return true;
}

std::string tickLabel(double v, double step)
{
	char buf[32];
	const int dec = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
	if (std::abs(v) < 1e-12 * step) v = 0;
	if (dec > 4)
		std::snprintf(buf, sizeof(buf), "%.1e", v);
	else
		std::snprintf(buf, sizeof(buf), "%.*f", dec, v);
	return buf;
}
}  // namespace

void CPlotCanvas::line(double x0, double y0, double x1, double y1, const TColor& c, int width)
{
	double ax = px(x0), ay = py(y0), bx = px(x1), by = py(y1);
	if (!std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(bx) || !std::isfinite(by))
		return;
	if (!clip(ax, ay, bx, by, m_left, m_top, m_left + m_width - 1, m_top + m_height - 1)) return;
	m_img.line(static_cast<int>(std::lround(ax)), static_cast<int>(std::lround(ay)),
	           static_cast<int>(std::lround(bx)), static_cast<int>(std::lround(by)), c,
	           static_cast<unsigned>(width));
}

void CPlotCanvas::polyline(const std::vector<Eigen::Vector2d>& pts, const TColor& c, int width,
                           int dash)
{
	const double on = dash, period = dash + std::max(1, dash / 2);
	double phase = 0;  // pixels walked along the line, modulo the period
	for (size_t i = 1; i < pts.size(); ++i)
	{
		if (!pts[i - 1].allFinite() || !pts[i].allFinite()) continue;
		if (dash <= 0)
		{
			line(pts[i - 1].x(), pts[i - 1].y(), pts[i].x(), pts[i].y(), c, width);
			continue;
		}
		const double len =
		    std::hypot(px(pts[i].x()) - px(pts[i - 1].x()), py(pts[i].y()) - py(pts[i - 1].y()));
		if (!std::isfinite(len)) continue;
		// The "on" pieces [a, b] of this segment, in pixels from its start.
		for (double a = 0; a < len;)
		{
			const double inPeriod = std::fmod(phase + a, period);
			const double piece = inPeriod < on ? on - inPeriod : period - inPeriod;
			const double b = std::min(len, a + piece);
			if (inPeriod < on)
			{
				const Eigen::Vector2d p = pts[i - 1] + (pts[i] - pts[i - 1]) * (a / len);
				const Eigen::Vector2d q = pts[i - 1] + (pts[i] - pts[i - 1]) * (b / len);
				line(p.x(), p.y(), q.x(), q.y(), c, width);
			}
			a = b;
		}
		phase = std::fmod(phase + len, period);
	}
}

void CPlotCanvas::mark(double x, double y, const TColor& c, char type, int size)
{
	const double u = px(x), v = py(y);
	if (!(u >= m_left && u < m_left + m_width && v >= m_top && v < m_top + m_height)) return;
	const int iu = static_cast<int>(std::lround(u)), iv = static_cast<int>(std::lround(v));
	if (type == '.')
		m_img.filledRectangle(iu - 1, iv - 1, iu + 1, iv + 1, c);
	else
		m_img.drawMark(iu, iv, c, type, size);
}

void CPlotCanvas::ellipse(const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov, double n_sigma,
                          const TColor& c, int width)
{
	if (!cov.allFinite() || !mean.allFinite()) return;
	const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (cov + cov.transpose()));
	if (es.eigenvalues()[0] < 0) return;
	const Eigen::Matrix2d A =
	    n_sigma * es.eigenvectors() * es.eigenvalues().cwiseSqrt().asDiagonal();
	constexpr int kPts = 36;
	std::vector<Eigen::Vector2d> pts;
	for (int i = 0; i <= kPts; ++i)
	{
		const double a = 2 * M_PI * i / kPts;
		pts.push_back(mean + A * Eigen::Vector2d(std::cos(a), std::sin(a)));
	}
	polyline(pts, c, width);
}

std::vector<double> niceTicks(double lo, double hi, int target)
{
	std::vector<double> t;
	if (!(hi > lo) || target < 1) return t;
	// Refine until at least 3 ticks fall inside (a 1-2-5 step can overshoot the target).
	for (int attempt = 0; attempt < 4 && t.size() < 3; ++attempt, target *= 2)
	{
		t.clear();
		const double raw = (hi - lo) / target;
		const double mag = std::pow(10.0, std::floor(std::log10(raw)));
		double step = mag;
		for (double f : {1.0, 2.0, 5.0, 10.0})
			if (f * mag >= raw)
			{
				step = f * mag;
				break;
			}
		for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step)
			t.push_back(v);
	}
	return t;
}

TColor lighter(const TColor& c, double amount)
{
	auto m = [amount](uint8_t v) { return static_cast<uint8_t>(v + amount * (255 - v)); };
	return TColor(m(c.R), m(c.G), m(c.B));
}

void CPlotCanvas::axes(const std::string& xlabel, const std::string& ylabel,
                       const std::string& title)
{
	const TColor black(0, 0, 0), grid(225, 225, 225);
	const int r = m_left + m_width - 1, b = m_top + m_height - 1;
	m_img.selectTextFont("6x13");
	const auto xt = niceTicks(m_world.xmin, m_world.xmax, std::max(2, m_width / 110));
	const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1;
	for (double v : xt)
	{
		const int u = static_cast<int>(std::lround(px(v)));
		m_img.line(u, m_top, u, b, grid);
		m_img.line(u, b, u, b + 5, black);
		const std::string s = tickLabel(v, xs);
		m_img.textOut(u - 3 * static_cast<int>(s.size()), b + 8, s, black);
	}
	const auto yt = niceTicks(m_world.ymin, m_world.ymax, std::max(2, m_height / 60));
	const double ys = yt.size() > 1 ? yt[1] - yt[0] : 1;
	for (double v : yt)
	{
		const int w = static_cast<int>(std::lround(py(v)));
		m_img.line(m_left, w, r, w, grid);
		m_img.line(m_left - 5, w, m_left, w, black);
		const std::string s = tickLabel(v, ys);
		m_img.textOut(m_left - 8 - 6 * static_cast<int>(s.size()), w - 6, s, black);
	}
	m_img.rectangle(m_left, m_top, r, b, black);
	m_img.selectTextFont("9x15");
	m_img.textOut(m_left + m_width / 2 - 4 * static_cast<int>(xlabel.size()), b + 24, xlabel,
	              black);
	m_img.textOut(m_left, m_top - 17, ylabel, black);
	m_img.selectTextFont("9x15B");
	m_img.textOut(m_left + m_width / 2 - 4 * static_cast<int>(title.size()), m_top - 19, title,
	              black);
}

int legendWidth(const std::vector<TLegendEntry>& entries)
{
	size_t longest = 0;
	for (const auto& e : entries) longest = std::max(longest, e.label.size());
	return 40 + 9 * static_cast<int>(longest) + 10;
}

void CPlotCanvas::legend(const std::vector<TLegendEntry>& entries, bool outside)
{
	if (entries.empty()) return;
	const int lineH = 16, w = legendWidth(entries);
	const int h = lineH * static_cast<int>(entries.size()) + 8;
	const int x0 = outside ? m_left + m_width + 10 : m_left + m_width - w - 6, y0 = m_top + 6;
	m_img.filledRectangle(x0, y0, x0 + w, y0 + h, TColor(255, 255, 255));
	m_img.rectangle(x0, y0, x0 + w, y0 + h, TColor(120, 120, 120));
	m_img.selectTextFont("9x15");
	for (size_t i = 0; i < entries.size(); ++i)
	{
		const auto& e = entries[i];
		const int y = y0 + 4 + lineH * static_cast<int>(i) + lineH / 2;
		if (e.marker == '.')
			m_img.filledRectangle(x0 + 17, y - 1, x0 + 19, y + 1, e.color);
		else if (e.marker)
			m_img.drawMark(x0 + 18, y, e.color, e.marker, 4);
		else if (e.dash <= 0)
			m_img.line(x0 + 6, y, x0 + 30, y, e.color, static_cast<unsigned>(e.width));
		else
			for (int a = 0; a < 24; a += e.dash + std::max(1, e.dash / 2))
				m_img.line(x0 + 6 + a, y, x0 + 6 + std::min(24, a + e.dash), y, e.color,
				           static_cast<unsigned>(e.width));
		m_img.textOut(x0 + 36, y - 7, e.label, TColor(0, 0, 0));
	}
}
}  // namespace dynslam::eval
