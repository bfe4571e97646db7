#pragma once
/** Hand-scripted steps for the back-end tests: an odometry action with a chosen covariance,
 * and a range-bearing frame of chosen world points seen from a known ego pose (noise-free or
 * with a seeded Cartesian noise). Every back-end (CDynamicKFSLAM2D and the framework's) takes
 * these through ISlamBackend::processActionObservation. */
#include <dynslam/common/odometry_action.h>
#include <dynslam/core/models/measurement.h>
#include <dynslam/core/models/se2.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace dynslam_test::script
{
/** The [DynamicKFSLAM] keys the scripted filter tests share (Cartesian readings, odometry noise
 * from the action); each test adds Sigma_0, Sigma_xi and its own keys. */
inline const std::string kFilterKeys =
    "[DynamicKFSLAM]\n"
    "measurement_model = cartesian\n"
    "Sigma_v = [1e-4 1e-4]\n"
    "motion_noise = action\n";
/** A CActionCollection with one CActionRobotMovement2D: increment u, covariance C. */
inline mrpt::obs::CActionCollection::Ptr action(const Eigen::Vector3d& u, const Eigen::Matrix3d& C)
{
	return dynslam::makeOdometryAction(u, C);
}

/** (landmark ID, world point) pairs seen in one step. */
using TSeen = std::vector<std::pair<int32_t, Eigen::Vector2d>>;

/** A sensory frame with the range-bearing readings of `seen` from ego pose x. With a non-null
 * rng, each reading gets Cartesian noise N(0, Sigma) in the sensor frame first. */
inline mrpt::obs::CSensoryFrame::Ptr frame(const Eigen::Vector3d& x, const TSeen& seen,
                                           std::mt19937* rng = nullptr,
                                           const Eigen::Matrix2d& Sigma = Eigen::Matrix2d::Zero())
{
	using namespace dynslam;
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	obs->sensorLabel = "RB";
	obs->maxSensorDistance = 1000.f;
	obs->fieldOfView_yaw = float(2 * M_PI);
	std::normal_distribution<double> N(0, 1);
	const Eigen::Matrix2d L = Sigma.llt().matrixL();
	for (const auto& [id, p] : seen)
	{
		Eigen::Vector2d z = models::cartesianObserve(x, p);
		if (rng) z += L * Eigen::Vector2d(N(*rng), N(*rng));
		const Eigen::Vector2d rb = models::cartesianToRangeBearing(z);
		mrpt::obs::CObservationBearingRange::TMeasurement m;
		m.range = float(rb[0]);
		m.yaw = float(models::wrapToPi(rb[1]));
		m.pitch = 0;
		m.landmarkID = id;
		obs->sensedData.push_back(m);
	}
	auto sf = mrpt::obs::CSensoryFrame::Create();
	sf->insert(obs);
	return sf;
}
}  // namespace dynslam_test::script
