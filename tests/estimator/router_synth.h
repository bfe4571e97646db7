#pragma once
/** Synthetic tracks for the classifying router's tests (test_classifying_router.cpp,
 * test_classify_groups.cpp). */
#include <dynslam/estimator/classifying_router.h>
#include <dynslam/models/se2.h>

#include <cmath>
#include <random>

namespace router_test
{
using namespace dynslam;
using namespace dynslam::estimator;

/** A robot driving along x with noisy odometry; world points seen in the robot frame
 * (Cartesian model, noise R = sigma^2 I). */
struct TSynth
{
	std::mt19937 rng;
	Eigen::Vector3d truth = Eigen::Vector3d::Zero();
	Eigen::Vector3d u_true{1.0, 0.0, 0.01};
	Eigen::Matrix3d U = Eigen::Vector3d(1e-4, 1e-4, 4e-6).asDiagonal();
	double sigma = 0.03;
	explicit TSynth(unsigned seed) : rng(seed) {}
	double n(double s) { return std::normal_distribution<double>(0, s)(rng); }
	/** Advances the robot; returns the noisy odometry increment. */
	Eigen::Vector3d move()
	{
		truth = models::composePose(truth, u_true);
		return u_true +
		       Eigen::Vector3d(n(std::sqrt(U(0, 0))), n(std::sqrt(U(1, 1))), n(std::sqrt(U(2, 2))));
	}
	Eigen::Vector2d see(const Eigen::Vector2d& world)
	{
		const Eigen::Vector2d q = models::rot2(truth[2]).transpose() * (world - truth.head<2>());
		return q + Eigen::Vector2d(n(sigma), n(sigma));
	}
	TRouterContext ctx(const Eigen::Vector3d& u) const
	{
		TRouterContext c;
		c.R = Eigen::Matrix2d::Identity() * sigma * sigma;
		c.u = u;
		c.U = U;
		return c;
	}
};

const auto kNone = [](int32_t) { return false; };
}  // namespace router_test
