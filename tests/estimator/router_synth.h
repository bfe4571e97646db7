#pragma once
/** Synthetic tracks for the classifying router's tests (test_classifying_router.cpp,
 * test_classify_groups.cpp, test_classify_hints.cpp, test_classify_static_test.cpp). */
#include <dynslam/core/models/se2.h>
#include <dynslam/estimator/classifying_router.h>

#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <vector>

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

/** Runs the router step by step: readings(k) gives the readings of step k (seen through s after
 * its move). Keeps the set of landmarks the filter would hold (StaticNew in, dropped
 * candidates out). */
struct TRouterRun
{
	CClassifyingRouter r;
	TSynth s;
	std::set<int32_t> inState;
	std::vector<TRoutedStep> out;
	TRouterRun(const TClassifyParams& p, unsigned seed) : r(p), s(seed) {}
	void runReadings(int steps, const std::function<std::vector<TReading>(int)>& readings)
	{
		for (int k = int(out.size()); k < steps; ++k)
		{
			r.setContext(s.ctx(k == 0 ? Eigen::Vector3d::Zero() : s.move()));
			out.push_back(
			    r.route(k, readings(k), [&](int32_t id) { return inState.count(id) != 0; }));
			for (const auto& m : out.back().readings)
				if (m.route == Route::StaticNew) inState.insert(m.reading.id);
			for (const int32_t id : out.back().dropped_candidates) inState.erase(id);
		}
	}
	/** The routed reading at step k whose position in the input was i. */
	const TRoutedReading& at(int k, size_t i) const { return out[size_t(k)].readings[i]; }
	/** A counter of TRoutedStep summed over the steps run. */
	size_t total(size_t TRoutedStep::*field) const
	{
		size_t n = 0;
		for (const auto& o : out) n += o.*field;
		return n;
	}
};
}  // namespace router_test
