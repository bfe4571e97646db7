#pragma once
/** @file chi2.h
 * Chi-square bounds of the evaluation: the interval of an average of NEES/NIS values over
 * independent runs. The distribution function and quantiles are core's (dynslam/core/chi2.h: pure
 * math, used by the estimators' gates too); the using-declarations keep them reachable as
 * dynslam::eval::chi2Quantile etc. for the evaluation's callers. */
#include <dynslam/core/chi2.h>

namespace dynslam::eval
{
using dynslam::chi2Cdf;
using dynslam::chi2Interval;
using dynslam::chi2Quantile;
using dynslam::TChi2Interval;

/** Bounds for the average of `runs` independent NEES/NIS values whose degrees of freedom add up
 * to total_dof (N runs of n dof each: total_dof = N n): the sum is chi2(total_dof), so the
 * average lies in [q((1-c)/2, total_dof), q((1+c)/2, total_dof)] / runs. Throws
 * std::invalid_argument for runs < 1. */
TChi2Interval averageChi2Bounds(double total_dof, int runs, double confidence = 0.95);
}  // namespace dynslam::eval
