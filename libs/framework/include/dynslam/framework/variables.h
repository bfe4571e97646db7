#pragma once
/** @file variables.h
 * Typed variable blocks of the optimization framework (paper Section II):
 *
 * | kind            | key fields                 | dim | angle entry |
 * |-----------------|----------------------------|-----|-------------|
 * | EgoPose         | step t                     | 3   | 2 (theta)   |
 * | StaticLandmark  | id                         | 2   | -           |
 * | ObjectFeature   | object a, feature k, step tau | 2 | -          |
 * | ObjectPose      | object a, step t (xi_t, relative to the object's time 0) | 3 (2 for
 * one-feature objects) | 2 if dim 3 | | ObjectBodyPose  | object a, step t (global pose of the
 * object's body frame; CubeSLAM-like) | 3 (or 2) | 2 if dim 3 |
 * | ObjectVelocity  | object a, step t (object_model = cv / ctrv: (vx, vy, omega), world frame) |
 * 3 (2 for one-feature objects) | - |
 *
 * A variable's value is a VectorXd; angle entries are kept wrapped to (-pi, pi]. */
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <tuple>

namespace dynslam::framework
{
enum class VarKind : uint8_t
{
	EgoPose,
	StaticLandmark,
	ObjectFeature,
	ObjectPose,
	ObjectBodyPose,
	ObjectVelocity
};

struct TVarKey
{
	VarKind kind = VarKind::EgoPose;
	int32_t id = -1;       ///< static landmark ID, or object index; -1 for ego poses
	int32_t feature = -1;  ///< feature index within the object (object features)
	int step = -1;         ///< time step (ego and object poses, object features); -1 for landmarks

	static TVarKey ego(int t) { return {VarKind::EgoPose, -1, -1, t}; }
	static TVarKey landmark(int32_t id) { return {VarKind::StaticLandmark, id, -1, -1}; }
	static TVarKey objectFeature(int32_t obj, int32_t k, int tau)
	{
		return {VarKind::ObjectFeature, obj, k, tau};
	}
	static TVarKey objectPose(int32_t obj, int t) { return {VarKind::ObjectPose, obj, -1, t}; }
	static TVarKey objectBodyPose(int32_t obj, int t)
	{
		return {VarKind::ObjectBodyPose, obj, -1, t};
	}

	static TVarKey objectVelocity(int32_t obj, int t)
	{
		return {VarKind::ObjectVelocity, obj, -1, t};
	}

	bool operator<(const TVarKey& o) const
	{
		return std::tie(kind, id, feature, step) < std::tie(o.kind, o.id, o.feature, o.step);
	}
	bool operator==(const TVarKey& o) const
	{
		return kind == o.kind && id == o.id && feature == o.feature && step == o.step;
	}
	bool operator!=(const TVarKey& o) const { return !(*this == o); }
};

/** Human-readable name, e.g. "x[12]", "landmark 7", "f[obj 1, k 2, t 5]", "xi[obj 1, t 5]". */
std::string toString(const TVarKey& k);

/** Index of the angle entry of a block of this kind and dimension, or -1. */
int angleIndex(VarKind kind, int dim);

/** a (-) b for two values of one block: the difference with the angle entry wrapped. */
Eigen::VectorXd blockMinus(VarKind kind, const Eigen::VectorXd& a, const Eigen::VectorXd& b);
/** a (+) d: the sum with the angle entry wrapped. */
Eigen::VectorXd blockPlus(VarKind kind, const Eigen::VectorXd& a, const Eigen::VectorXd& d);
}  // namespace dynslam::framework
