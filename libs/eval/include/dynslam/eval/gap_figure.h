#pragma once
/** @file gap_figure.h
 * The ego position error over the road with the landmark gaps shaded (issue 13): x = the true
 * ego x [m] (the highway runs along x), y = |position error| [m], one line per series. */
#include <dynslam/eval/figures.h>

#include <utility>
#include <vector>

namespace dynslam::eval
{
mrpt::img::CImage drawGapErrorFigure(const io::TGroundTruth& gt,
                                     const std::vector<TFigureSeries>& series,
                                     const std::vector<std::pair<double, double>>& gaps,
                                     int width = 1400, int height = 600);
}  // namespace dynslam::eval
