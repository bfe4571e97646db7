#pragma once
/** @file object_pose_step.h
 * Alg. 4 (object-pose augmentation) as a term of the running cost, shared by every back-end
 * of the framework (CAlg1Backend, CWindowBackend). Pure Eigen. */
#include <dynslam/framework/running_cost.h>
#include <dynslam/framework/terms.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace dynslam::framework
{
/** What addObjectPose did. */
enum class PoseStep
{
	Added,      ///< xi_t added with its residual
	NotSeen,    ///< no time-t feature of the object in newT
	Degenerate  ///< rotation undetermined (one feature of a rigid object, coinciding features)
};

/** Adds the pose xi_t of object `obj` to the cost, initialized by gamma(f_0, f_t), with the
 * pose-space residual xi - gamma(f_0, f_t) (exactly Alg. 4, Theorem 4.1) or the paper's
 * feature-space residual f_t - g^o(xi, f_0) (`poseSpace` false).
 * @param features the feature indices of the object's features seen at its time 0
 * (`first_step`), in the registry's order (estimator::TObjectEntry::feature_index).
 * @param newT the time-t feature variables added this step (any objects).
 * @param k out: the keys of the new term (k.pose is the new variable when Added). */
PoseStep addObjectPose(CRunningCost& c, int32_t obj, int first_step,
                       const std::vector<int32_t>& features, const std::vector<TVarKey>& newT,
                       int step, bool poseSpace, const Eigen::Matrix2d& Sigma_xi,
                       TObjectPoseKeys& k);
}  // namespace dynslam::framework
