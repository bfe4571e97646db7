#pragma once
/** @file mrpt_static_association.h
 * The static association of ID -1 readings under feature_labels = classify
 * (estimator/unknown_id_association.h), with MRPT's
 * mrpt::slam::data_association_full_covariance as CRangeBearingKFSLAM2D uses it: observations
 * and predictions are points in the robot frame, the predictions' covariance is block diagonal
 * (the router's static-hypothesis filters are independent; each block includes the reading
 * noise), method / metric / IC chi-square / IC metric / IC ML threshold from the classify_assoc_*
 * keys. */
#include <dynslam/estimator/unknown_id_association.h>

namespace dynslam
{
/** Throws std::invalid_argument on an unknown method or metric name. */
estimator::StaticAssociationFn makeMrptStaticAssociation(const estimator::TUnknownIdParams& p);
}  // namespace dynslam
