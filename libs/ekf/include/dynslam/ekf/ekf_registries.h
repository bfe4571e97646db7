#pragma once
/** @file ekf_registries.h
 * The update engines of the EKF: estimator::updateEngines() (pure Eigen) plus the engines that
 * need MRPT's slam library, registered here: jcbb (CJcbbUpdateEngine, made through
 * slam_services.h so that a program may load it late). MRPT's own update (static_update = mrpt,
 * CMrptUpdateEngine) is bound to its filter and chosen by static_update, not outlier_method. */
#include <dynslam/estimator/seam_registries.h>

namespace dynslam
{
/** outlier_method -> engine: gate, none, huber, cauchy, gate_recovery, jcbb. */
const estimator::CUpdateEngineRegistry& ekfUpdateEngines();
}  // namespace dynslam
