#pragma once
// A small hand-made ground truth shared by the eval tests.
#include <dynslam/io/ground_truth.h>

#include <cmath>
#include <limits>

namespace eval_test
{
/** 4 steps (t = 0, 0.5, 1, 1.5), ego along x with heading near pi at step 3; landmarks 1, 2, 5;
 * object 0 (two features, first seen at step 1) and object 1 (one feature, first seen at 0). */
inline dynslam::io::TGroundTruth smallGroundTruth()
{
	const double nan = std::numeric_limits<double>::quiet_NaN();
	dynslam::io::TGroundTruth gt;
	gt.t = {0.0, 0.5, 1.0, 1.5};
	gt.ego = {{0, 0, 0}, {1, 0, 0.1}, {2, 0.5, 0.2}, {3, 1, M_PI - 0.01}};
	gt.landmarks = {{1, {10, 5}}, {2, {20, -5}}, {5, {30, 5}}};
	dynslam::io::TObjectGroundTruth a;
	a.object = 0;
	a.num_features = 2;
	a.first_step = 1;
	dynslam::io::TObjectGroundTruth b;
	b.object = 1;
	b.num_features = 1;
	b.first_step = 0;
	for (int k = 0; k < 4; ++k)
	{
		Eigen::Matrix2Xd fa(2, 2);
		fa << 5 + k, 7 + k, 2, 2;
		a.features.push_back(fa);
		a.pose.push_back(k < 1 ? Eigen::Vector3d(nan, nan, nan) : Eigen::Vector3d(k - 1, 0, 0));
		a.visible.push_back(k >= 1);
		Eigen::Matrix2Xd fb(2, 1);
		fb << 0, -3 + 0.5 * k;
		b.features.push_back(fb);
		b.pose.push_back(Eigen::Vector3d(0, 0.5 * k, 0));
		b.visible.push_back(1);
	}
	gt.objects = {a, b};
	return gt;
}
}  // namespace eval_test
