#pragma once
/** @file figures.h
 * PNG figures drawn headless with mrpt::img::CImage (no display needed):
 *  - drawMapFigure: ground-truth ego path, the estimated ego paths of several filters (one
 *    colour each, with a legend), ground-truth landmarks, estimated landmarks with n-sigma
 *    covariance ellipses, and object tracks (truth: centroid of the object's features per step;
 *    estimate: centroid of the time-0 feature estimates moved by the estimated pose xi);
 *  - drawEgoErrorFigure: ego x, y, theta errors over time with +-n-sigma bounds;
 *  - drawConsistencyFigure: a NEES/NIS series (average over runs) with its chi-square bounds.
 *
 * The legends sit right of the plot area (never on the data).
 *
 * Highway aspect (1 km x ~60 m): by default the map is scaled non-uniformly (x and y fill the
 * image independently; the axis ticks show the true metres), so lateral detail stays visible.
 * Set equal_aspect for a metric-true picture, or `view` to zoom into a window. */
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/estimates.h>
#include <dynslam/eval/plot_canvas.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/img/CImage.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dynslam::eval
{
/** One filter's estimates to draw (not owned). */
struct TFigureSeries
{
	std::string name;
	mrpt::img::TColor color;
	const TRunEstimates* est = nullptr;
};

/** A distinct colour for series i (red, blue, green, orange, purple, ...). */
mrpt::img::TColor seriesColor(size_t i);

/** Line width and dash (CPlotCanvas::polyline) of series i of n, drawn in that order: earlier
 * series wider (2 + 2 (n-1-i) pixels, at most 8) and every other one dashed, the last solid, so
 * that a series drawn on top of another (e.g. `dynamic_classified` on `dynamic`) leaves it
 * visible. The legend shows the same style. */
struct TSeriesStyle
{
	int width = 2;
	int dash = 0;
};
TSeriesStyle seriesStyle(size_t i, size_t n);

/** More agents than this: one grouped legend entry for them instead of one each. */
constexpr size_t kMaxAgentLegendEntries = 6;

struct TMapFigureOptions
{
	int width = 1600, height = 700;
	bool equal_aspect = false;  ///< false: non-uniform scaling (fills the image)
	std::optional<TBox> view;   ///< zoom window (world); default: all content + 3% margin
	double sigma = 3;           ///< ellipses at n sigma
	bool show_landmarks = true, show_ellipses = true, show_objects = true;
	std::string title = "Map";
};

/** Draws the map figure; gt may be null (estimates only). */
mrpt::img::CImage drawMapFigure(const io::TGroundTruth* gt,
                                const std::vector<TFigureSeries>& series,
                                const TMapFigureOptions& opt = {});

struct TErrorFigureOptions
{
	int width = 1400, height = 900;
	double sigma = 3;
	std::string title = "Ego pose error";
	bool time_axis = true;  ///< x axis: t [s] (else step index)
};

/** Three stacked panels (x, y, theta error) for every series, with +-sigma bounds in a lighter
 * shade of the series colour. */
mrpt::img::CImage drawEgoErrorFigure(const io::TGroundTruth& gt,
                                     const std::vector<TFigureSeries>& series,
                                     const TErrorFigureOptions& opt = {});

struct TConsistencyFigureOptions
{
	int width = 1200, height = 500;
	std::string title;  ///< default: the stats' name
	std::string xlabel = "step";
};

/** The average NEES/NIS per key with the lower and upper chi-square bounds (grey). The
 * y range is clipped at 3x the largest upper bound; values above are drawn at the top edge. */
mrpt::img::CImage drawConsistencyFigure(const TConsistencyStats& stats,
                                        const TConsistencyFigureOptions& opt = {});

/** Saves as PNG (or by extension); throws std::runtime_error naming the path on failure. */
void savePng(const mrpt::img::CImage& img, const std::string& path);

/** Estimated object tracks, per object: the centroid of its time-0 feature estimates moved by
 * xi_xy, at each pose estimate in step order; a NaN point breaks the line where steps are
 * missing. Objects without feature estimates are left out. */
std::map<int32_t, std::vector<Eigen::Vector2d>> estimatedObjectTracks(const TRunEstimates& est);
}  // namespace dynslam::eval
