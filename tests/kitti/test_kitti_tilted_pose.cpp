/** The ego heading of a camera pose with pitch and roll (geometry.h, issue 32 "Test gaps to
 * close"): for a pure rotation about the camera's y axis every pair of rotation entries gives
 * the same angle, so the importer's formula is pinned here on poses that also pitch and roll.
 *
 * A vehicle with heading a (about the world's "down" axis y), then pitch p (about the camera's
 * x axis) and roll r (about its z axis): R = R_y(a) R_x(p) R_z(r). Its forward (z) axis is
 * R_y(a) R_x(p) e_z = (sin a cos p, -sin p, cos a cos p): in the ground plane (forward = z,
 * left = -x) it points along (cos a, -sin a) cos p, so the ego heading is -a exactly for
 * |p| < pi/2, whatever the roll. (Its x axis, R_y(a) R_x(p) R_z(r) e_x, leaves the heading
 * with roll and pitch together: an importer reading it would be off by up to 3.4 degrees below.) */
#include <dynslam/core/models/se2.h>
#include <dynslam/kitti/geometry.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynslam;
using namespace dynslam::kitti;

namespace
{
Eigen::Matrix3d rotX(double p)
{
	Eigen::Matrix3d R;
	R << 1, 0, 0, 0, std::cos(p), -std::sin(p), 0, std::sin(p), std::cos(p);
	return R;
}
Eigen::Matrix3d rotY(double a)
{
	Eigen::Matrix3d R;
	R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
	return R;
}
Eigen::Matrix3d rotZ(double r)
{
	Eigen::Matrix3d R;
	R << std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r), 0, 0, 0, 1;
	return R;
}
TCameraPose pose(double a, double p, double r, const Eigen::Vector3d& t)
{
	TCameraPose T;
	T.leftCols<3>() = rotY(a) * rotX(p) * rotZ(r);
	T.col(3) = t;
	return T;
}
}  // namespace

TEST(KittiGeometry, EgoHeadingOfAPitchedAndRolledCamera)
{
	for (const double a : {0.0, 0.4, -1.1, 2.6})
		for (const double p : {0.05, -0.12, 0.3})
			for (const double r : {0.04, -0.2})
			{
				const Eigen::Vector3d e = egoPoseFromCamera(pose(a, p, r, {2, -1, 5}));
				EXPECT_NEAR(e.x(), 5, 1e-15);
				EXPECT_NEAR(e.y(), -2, 1e-15);
				EXPECT_NEAR(models::wrapToPi(e.z() + a), 0, 1e-12)
				    << "a " << a << " pitch " << p << " roll " << r;
			}
}

TEST(KittiGeometry, EgoHeadingLiteralValues)
{
	// a = 0.4, p = 0.3, r = -0.2: the forward axis (sin 0.4 cos 0.3, -sin 0.3, cos 0.4 cos 0.3)
	// = (0.372026, -0.295520, 0.879923), heading atan2(-0.372026, 0.879923) = -0.4.
	const TCameraPose T = pose(0.4, 0.3, -0.2, {0, 0, 0});
	EXPECT_NEAR(T(0, 2), 0.372026, 1e-6);
	EXPECT_NEAR(T(1, 2), -0.295520, 1e-6);
	EXPECT_NEAR(T(2, 2), 0.879923, 1e-6);
	EXPECT_NEAR(egoPoseFromCamera(T).z(), -0.4, 1e-12);
	// The x axis of this pose, (0.879838, -0.189796, -0.435732) to 6 digits, would give
	// atan2(-0.435732, 0.879838) = -0.4598: 3.4 degrees off.
	EXPECT_NEAR(T(0, 0), 0.879838, 1e-6);
	EXPECT_NEAR(T(2, 0), -0.435732, 1e-6);
	EXPECT_NEAR(std::atan2(T(2, 0), T(0, 0)), -0.459833, 1e-6);
}
