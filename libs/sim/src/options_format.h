#pragma once
/** @file options_format.h
 * Internal: number formatting shared by the scenario options reader and writer. */
#include <dynslam/sim/motion.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace dynslam::sim::detail
{
/** Shortest of 15..17 significant digits that reads back to the same double. */
std::string fmt(double v);
/** `[a b; c d]` with fmt() entries. */
std::string fmtMatrix(const Eigen::MatrixXd& m);
/** `[t d target; ...]`. */
std::string fmtRamps(const std::vector<TRamp>& r);
}  // namespace dynslam::sim::detail
