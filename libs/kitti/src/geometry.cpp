#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/geometry.h>

#include <cmath>

namespace dynslam::kitti
{
Eigen::Vector3d egoPoseFromCamera(const TCameraPose& T)
{
	return {T(2, 3), -T(0, 3), std::atan2(-T(0, 2), T(2, 2))};
}

Eigen::Vector2d cameraToEgo(double x_cam, double z_cam) { return {z_cam, -x_cam}; }

double boxYawEgo(double ry) { return models::wrapToPi(-ry - M_PI / 2); }

Eigen::Vector2d boxCentreEgo(const TKittiBox& b) { return cameraToEgo(b.x, b.z); }

Eigen::Matrix<double, 2, 4> footprintCornersEgo(const TKittiBox& b)
{
	Eigen::Matrix<double, 2, 4> box;
	const double L = b.l / 2, W = b.w / 2;
	box << L, L, -L, -L, W, -W, -W, W;
	const Eigen::Matrix<double, 2, 4> c = models::rot2(boxYawEgo(b.ry)) * box;
	return c.colwise() + boxCentreEgo(b);
}

Eigen::Vector2d egoToWorld(const Eigen::Vector3d& pose, const Eigen::Vector2d& p)
{
	return pose.head<2>() + models::rot2(pose.z()) * p;
}

Eigen::Vector2d rangeBearing(const Eigen::Vector2d& p)
{
	return {p.norm(), std::atan2(p.y(), p.x())};
}
}  // namespace dynslam::kitti
