#pragma once
/** @file covariance_writer.h
 * The full covariances of a run (--full-covariance of dynslam-run and dynslam-compare), so
 * that others can compute NEES with their own ground truth. Format of `covariance.txt`
 * (version 1): lines starting with '#' are comments; every other line is whitespace-separated,
 * a record type, its keys, then a matrix in row-major order, each number written with 17
 * significant digits (reads back to the same double):
 *
 *   ego STEP T  c00 c01 c02 c10 c11 c12 c20 c21 c22        ego (x, y, theta), one per step
 *   landmark ID  c00 c01 c10 c11                            final static landmark (x, y)
 *   landmarks_joint_ids N ID_1 ... ID_N                     order of the joint covariance
 *   landmarks_joint_row I v_0 ... v_{2N-1}                  row I (0..2N-1) of the 2N x 2N joint
 *   object_feature OBJECT FEATURE  c00 c01 c10 c11          time-0 feature (x, y)
 *   object_pose OBJECT STEP DIM  c00 ... (DIM x DIM)         xi = (dx, dy[, dtheta]), DIM 2 or 3
 *
 * Order: all ego lines (by step), then the landmarks (by ID), the joint landmark covariance if
 * the back-end has one (rows 2i, 2i+1 belong to ID_{i+1}), the object features, the object
 * poses. T is the step's time stamp (the rawlog's), "nan" if unknown. */
#include <dynslam/eval/estimates.h>

#include <ostream>

namespace dynslam::eval
{
void writeCovariances(std::ostream& os, const TRunEstimates& est);
}  // namespace dynslam::eval
