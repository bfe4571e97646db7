#pragma once
/** @file world_blocks.h
 * (Internal to dynslam::ekf.) One object's blocks in a layout and its registry entry: what an
 * object's world pose (world_poses.cpp) and velocity (CDynamicKFSLAM2D::getObjectVelocity) read. */
#include <dynslam/estimator/object_registry.h>
#include <dynslam/estimator/state_layout.h>

#include <climits>
#include <cstdint>
#include <map>

namespace dynslam::ekf
{
/** The blocks of one object in a layout: its newest pose, its velocity, its f_0 by feature ID
 * (SIZE_MAX: none). */
struct TWorldBlocks
{
	size_t pose = SIZE_MAX, vel = SIZE_MAX;
	std::map<int32_t, size_t> f0;
};
TWorldBlocks worldBlocksOf(const estimator::CPaddedLayout& L, int32_t obj);

/** The registry's entry of obj; throws std::invalid_argument naming CDynamicKFSLAM2D::`who` for
 * an object the filter does not know. */
const estimator::TObjectEntry& entryOf(const estimator::CObjectRegistry& reg, int32_t obj,
                                       const char* who);
}  // namespace dynslam::ekf
