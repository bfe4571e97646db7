#pragma once
/** @file class_figures.h
 * Figures of online static / moving classification (feature_labels = classify, issue 12;
 * doc/results/classification.md "Figures"), headless PNG through plot_canvas.h:
 *  - drawClassMap: the final map coloured by the decided class: the estimated ego path, every
 *    static landmark of the final map (blue square; orange if its readings are truly moving or
 *    clutter: a wrong static landmark), the tracks decided moving (estimated object tracks, red,
 *    f_0 marked 'x'), over the true ego path and landmarks (grey) when given;
 *  - drawDecisionTimeline: one row per track (written ID >= 0), x = step; at each reading the
 *    decision (upper band: grey undecided, blue static, red moving) and, if the truth is given,
 *    the true class (lower band: blue static, red moving, black clutter). Rows sorted by true
 *    class then first step; at most max_rows rows (the first ones; the title says how many). */
#include <dynslam/eval/class_metrics.h>
#include <dynslam/eval/estimates.h>
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/ground_truth.h>
#include <mrpt/img/CImage.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dynslam::eval
{
/** The decision about every reading of a run, in rawlog order, with its step and written ID. */
struct TReadingDecisions
{
	std::vector<int> steps;
	std::vector<int32_t> ids;  ///< the ID the filter used (-1 readings: the track it resolved)
	std::vector<Decision> decisions;
};

/** truth: the class truth in the same order (may be empty); gt may be null. */
mrpt::img::CImage drawClassMap(const io::TGroundTruth* gt, const TRunEstimates& est,
                               const std::vector<io::TReadingClass>& truth,
                               const std::string& title, int width = 1600, int height = 700);

mrpt::img::CImage drawDecisionTimeline(const TReadingDecisions& d,
                                       const std::vector<io::TReadingClass>& truth,
                                       const std::string& title, int max_rows = 200);
}  // namespace dynslam::eval
