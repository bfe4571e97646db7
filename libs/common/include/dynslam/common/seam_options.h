#pragma once
/** @file seam_options.h
 * The [DynamicKFSLAM] options (model_options.h) as the parameters of the estimator's seam
 * registries (dynslam/estimator/seam_registries.h): the one translation from keys to seam
 * parameters, shared by the EKF, the framework's back-ends and the apps. */
#include <dynslam/common/model_options.h>
#include <dynslam/estimator/seam_registries.h>

#include <string>

namespace dynslam
{
/** object_model's parameters (cv.gate: the chi-square threshold of cv_gate). */
estimator::TObjectMotionParams objectMotionParams(const TModelOptions& o);
/** outlier_method's parameters. */
estimator::TUpdateEngineParams updateEngineParams(const TModelOptions& o);
/** The state lifecycle's name (compressed with static_update = compressed, else full) and its
 * parameters. */
std::string stateLifecycleName(const TModelOptions& o);
estimator::TLifecycleParams lifecycleParams(const TModelOptions& o);
}  // namespace dynslam
