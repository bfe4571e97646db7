#pragma once
/** @file mode_figure.h
 * The mode probabilities of multiple-model objects (object_model = mm, issue 28 item 5) over
 * time: one panel per object (the first max_objects by ID), one line per mode. */
#include <dynslam/eval/estimates.h>
#include <mrpt/img/CImage.h>

namespace dynslam::eval
{
struct TModeFigureOptions
{
	int width = 1000;
	int panel_height = 160;  ///< pixels per object
	size_t max_objects = 8;
	std::string title = "Object mode probabilities";
};

/** True if est has mode probabilities to draw (a multiple-model back-end's run). */
bool hasModeProbabilities(const TRunEstimates& est);

/** The figure; throws std::invalid_argument if !hasModeProbabilities(est). */
mrpt::img::CImage drawModeFigure(const TRunEstimates& est, const TModeFigureOptions& opt = {});
}  // namespace dynslam::eval
