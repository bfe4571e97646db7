#pragma once
/** @file assignment.h
 * Minimum-cost assignment of a rectangular cost matrix (the Hungarian method, Kuhn 1955 /
 * Munkres 1957, in the O(n^2 m) shortest-augmenting-path form with row and column potentials).
 * MRPT 2.5 has no rectangular assignment solver (its data association offers nearest neighbour
 * and JCBB), so the project keeps this small one. Pure C++/Eigen. doc/metrics.md "Multi-object
 * tracking" and the box tracker (estimator/box_tracker.h). */
#include <Eigen/Core>
#include <vector>

namespace dynslam::models
{
/** Solves min sum_i cost(i, a(i)) over one-to-one partial assignments a: rows -> columns.
 * Entries that are +infinity (or NaN) are forbidden pairs. Among all assignments the result
 * first has the largest number of allowed pairs, then the smallest total cost of them (the
 * rule of the KITTI tracking devkit, which gives forbidden pairs a prohibitive cost).
 * Returns, per row, the assigned column or -1. Throws std::invalid_argument on -infinity. */
std::vector<int> solveAssignment(const Eigen::MatrixXd& cost);
}  // namespace dynslam::models
