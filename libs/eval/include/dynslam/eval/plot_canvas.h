#pragma once
/** @file plot_canvas.h
 * A minimal headless 2-D plot on an mrpt::img::CImage: a world -> pixel transform for one plot
 * area (y up), clipped lines and polylines, marks, covariance ellipses, axes with "nice" ticks
 * and labels, and a legend. Used by figures.h; usable for other plots.
 *
 * Scaling: with equal_aspect the world box is enlarged along one axis so that one metre is the
 * same number of pixels in x and y; without it, x and y are scaled independently to fill the
 * plot area (non-uniform scaling, e.g. a 1 km x 60 m highway on a 1600 x 600 image). Ellipses
 * and all geometry go through the same transform, so they stay correct under either scaling. */
#include <mrpt/img/CImage.h>
#include <mrpt/img/TColor.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace dynslam::eval
{
/** An axis-aligned box in world coordinates. */
struct TBox
{
	double xmin = 0, xmax = 1, ymin = 0, ymax = 1;
	bool valid() const { return xmax > xmin && ymax > ymin; }
	/** Grows the box to contain (x, y) (ignores non-finite points). */
	void expand(double x, double y);
	/** Adds a relative margin on every side; a zero extent gets +-0.5 (or +-|center|/10). */
	TBox withMargin(double fraction) const;
	/** An empty box that any expand() replaces. */
	static TBox empty();
};

/** One legend line: a short line (marker == 0, drawn with width and dash) or a mark ('x', '+',
 * 's', '.'). */
struct TLegendEntry
{
	std::string label;
	mrpt::img::TColor color;
	char marker = 0;
	int width = 2;
	int dash = 0;  ///< as CPlotCanvas::polyline
};

/** Pixel width of the legend box of these entries (for a margin that holds it). */
int legendWidth(const std::vector<TLegendEntry>& entries);

class CPlotCanvas
{
public:
	/** Plot area of the image: pixels [left, left + width) x [top, top + height). */
	CPlotCanvas(mrpt::img::CImage& img, int left, int top, int width, int height, const TBox& world,
	            bool equal_aspect);

	double px(double x) const;  ///< world x -> pixel column
	double py(double y) const;  ///< world y -> pixel row (y up)
	const TBox& world() const { return m_world; }

	/** A world-coordinate segment, clipped to the plot area. */
	void line(double x0, double y0, double x1, double y1, const mrpt::img::TColor& c,
	          int width = 1);
	/** Consecutive points joined; non-finite points break the line. dash > 0: dashed, `dash`
	 * pixels on and dash / 2 off, the pattern running on along the whole polyline. */
	void polyline(const std::vector<Eigen::Vector2d>& pts, const mrpt::img::TColor& c,
	              int width = 1, int dash = 0);
	/** A mark ('x', '+', 's' square, '.' dot) at a world point, if inside the plot area. */
	void mark(double x, double y, const mrpt::img::TColor& c, char type, int size = 4);
	/** The n_sigma ellipse {p : (p-mean)^T cov^-1 (p-mean) = n_sigma^2} (skipped if cov is not
	 * positive semi-definite or not finite). */
	void ellipse(const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov, double n_sigma,
	             const mrpt::img::TColor& c, int width = 1);
	/** Frame, ticks with labels on both axes, axis labels and a title above the area. */
	void axes(const std::string& xlabel, const std::string& ylabel, const std::string& title);
	/** Legend box in the top-right corner of the plot area, or (outside) right of the plot
	 * area, top-aligned: the caller leaves legendWidth() + 10 pixels of margin there. */
	void legend(const std::vector<TLegendEntry>& entries, bool outside = false);

private:
	mrpt::img::CImage& m_img;
	int m_left, m_top, m_width, m_height;
	TBox m_world;
	double m_sx = 1, m_sy = 1;
};

/** Tick positions covering [lo, hi] with a 1-2-5 step and about `target` ticks. */
std::vector<double> niceTicks(double lo, double hi, int target);

/** A light version of a colour (blended with white by `amount` in [0, 1]). */
mrpt::img::TColor lighter(const mrpt::img::TColor& c, double amount = 0.55);
}  // namespace dynslam::eval
