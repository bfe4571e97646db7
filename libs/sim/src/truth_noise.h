#pragma once
/** @file truth_noise.h
 * The model-matched truth (issue 13, doc/simulator.md "Model-matched truth"): a true start pose
 * drawn from the filter's prior N(0, Sigma_0), and objects whose poses follow the CV model of
 * models/object_motion.h with white acceleration. Both off by default (no draws, the ground truth
 * is the deterministic one). Private to libs/sim. */
#include <dynslam/sim/TScenarioOptions.h>

#include <Eigen/Core>
#include <vector>

namespace dynslam::sim::detail
{
/** The ego's true start pose: a draw of N(0, Sigma_0) with a private generator seeded with
 * (noise_seed + 0x3C6EF372) mod 2^32 when o.start_from_prior, else exactly 0. */
Eigen::Vector3d trueStartPose(const TScenarioOptions& o);

/** Per object (numObjects) and step (o.numSteps()), the offset delta_k of its pose xi from the
 * deterministic one: per axis i, (delta_i, its rate) starts at 0 and follows the discrete CV
 * model with white acceleration q_i = o.object_accel_psd[i] over o.dt (models::cvProcessNoise).
 * Objects in index order, one private generator seeded with (noise_seed + 0x78DDE6E6) mod 2^32.
 * Empty when the PSD is zero. */
std::vector<std::vector<Eigen::Vector3d>> objectPoseOffsets(const TScenarioOptions& o,
                                                            size_t numObjects);

/** The features F (world, 2 x n) rotated by d[2] about their centroid, then moved by
 * d.head<2>(): the world features of pose xi + d when F are those of xi (the g^o convention of
 * models/object_pose.h rotates about the time-0 centroid, which xi carries to F's centroid). */
Eigen::Matrix2Xd offsetFeatures(const Eigen::Matrix2Xd& F, const Eigen::Vector3d& d);
}  // namespace dynslam::sim::detail
