#pragma once
/** @file world_common.h
 * What the two synthetic worlds of the benchmarks and the soak tests (synthetic_world.h,
 * soak_world.h) build alike: the ring of landmarks, the objects in convoy with the ego, the
 * range-bearing observation and one noisy reading of it. Header only. The random draws (the
 * reading's noise) are made in the same order as each world made them itself. */
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

namespace dynslam_bench
{
/** Landmark i of a ring of `landmarks` round the circle of radius R centred at (0, R) (the ego
 * starts at the origin heading +x), alternately inside and outside it by 3..10 m. */
inline Eigen::Vector2d ringLandmark(int i, int landmarks, double R)
{
	const double a = 2 * M_PI * i / landmarks;
	const double off = ((i % 2) ? 1.0 : -1.0) * (3.0 + 7.0 * ((i * 7919) % 101) / 100.0);
	const double r = R + off;
	return Eigen::Vector2d(r * std::sin(a), R - r * std::cos(a));
}

/** Body pose of convoy object a at step k: ego pose x (+) an offset 6..22 m ahead, 4 m or more
 * to the side (alternating), turning slowly in its own frame. */
inline Eigen::Vector3d convoyBody(const Eigen::Vector3d& x, int a, int k)
{
	const double side = (a % 2 == 0) ? 1.0 : -1.0;
	const Eigen::Vector3d off(6.0 + 4.0 * (a / 2 % 5), side * (4.0 + 3.0 * (a / 10)),
	                          0.02 * k * (1 + a % 3));
	return dynslam::models::composePose(x, off);
}

/** Feature f of convoy object a in the world, its body pose `body`. */
inline Eigen::Vector2d convoyFeature(const Eigen::Vector3d& body, int a, int f)
{
	const double ang = 2.1 * f + a;
	const Eigen::Vector2d local = Eigen::Vector2d(std::cos(ang), std::sin(ang)) * (0.8 + 0.3 * f);
	return body.head<2>() + dynslam::models::rot2(body[2]) * local;
}

/** An empty all-round range-bearing observation ("RB") with the sensor's range. */
inline mrpt::obs::CObservationBearingRange::Ptr makeObservation(double range)
{
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	obs->sensorLabel = "RB";
	obs->maxSensorDistance = float(range);
	obs->fieldOfView_yaw = float(2 * M_PI);
	return obs;
}

/** Appends the reading of point f from ego pose x with ID `id`: Cartesian, plus N(0, Sigma_v)
 * (diagonal; x then y drawn from n), as range and bearing. */
inline void addReading(mrpt::obs::CObservationBearingRange& obs, const Eigen::Vector3d& x,
                       int32_t id, const Eigen::Vector2d& f, const Eigen::Matrix2d& Sigma_v,
                       std::mt19937& rng, std::normal_distribution<double>& n)
{
	Eigen::Vector2d z = dynslam::models::cartesianObserve(x, f);
	z[0] += n(rng) * std::sqrt(Sigma_v(0, 0));
	z[1] += n(rng) * std::sqrt(Sigma_v(1, 1));
	const Eigen::Vector2d rb = dynslam::models::cartesianToRangeBearing(z);
	mrpt::obs::CObservationBearingRange::TMeasurement m;
	m.range = float(rb[0]);
	m.yaw = float(rb[1]);
	m.pitch = 0;
	m.landmarkID = id;
	obs.sensedData.push_back(m);
}
}  // namespace dynslam_bench
