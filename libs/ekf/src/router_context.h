#pragma once
/** @file router_context.h
 * (Internal to dynslam::ekf.) What CDynamicKFSLAM2D gives its router each step
 * (estimator::TRouterContext, set before route()) and the box tracks it reports:
 *  - staticInnovation (TRouterContext::static_innovation; the classifying router's
 *    classify_static_test = map, doc/results/classification.md): the innovation of a reading
 *    against a static landmark of the state, with the ego predicted by the step's odometry;
 *  - boxPrediction (TRouterContext::box_prediction; feature_labels = boxes, issue 31,
 *    doc/boxes.md): the joint prediction of a box whose four corners are static landmarks;
 *  - trackedBoxes (CDynamicKFSLAM2D::trackedBoxes): the box tracks of the step by [BoxTracker]'s
 *    output rule, a parked car held as four landmarks at the map's centre, every other box as
 *    the tracker has it, relative to the pose that placed it. A moving object's pose in the
 *    filter is that of its founders' centroid, the box centre only when all four corners
 *    founded it: measured worse on 0000-0010 (doc/boxes.md), so it is not used.
 * Everything here reads the filter (TFilterView) and changes nothing. */
#include <array>
#include <vector>

#include "modules/filter_module.h"

namespace dynslam::ekf
{
/** The step's context for the router (its callbacks read the filter through v's facade). */
estimator::TRouterContext routerContext(const TFilterView& v);

/** The innovation of reading z against static landmark id with the ego predicted as
 * propagateEgo() will (without first-estimate Jacobians); false if id is not a landmark of the
 * state, or with the odometry bias (the prediction also moves with the bias block: not
 * modelled here). */
bool staticInnovation(const TFilterView& v, int32_t id, const Eigen::Vector2d& z,
                      estimator::TStaticInnovation& out);

/** The footprint centre c (world) of the box whose corners are the static landmarks ids, the
 * mean of the four corners, with its covariance C; false if a corner is not in the state. */
bool boxPrediction(const TFilterView& v, const std::array<int32_t, 4>& ids, Eigen::Vector2d& c,
                   Eigen::Matrix2d& C);

/** The box tracks of the last step (robot frame; empty without a box tracker). */
std::vector<TTrackedBox> trackedBoxes(const TFilterView& v);
}  // namespace dynslam::ekf
