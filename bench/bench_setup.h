#pragma once
/** @file bench_setup.h
 * Shared set-up of dynslam-bench: the shipped highway rawlog, in-memory simulated runs, and the
 * two filters configured alike. */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace dynslam_bench
{
/** (action, sensory frame) pairs of one run. */
struct TRun
{
	std::vector<mrpt::obs::CActionCollection::Ptr> actions;
	std::vector<mrpt::obs::CSensoryFrame::Ptr> frames;
	Eigen::Matrix2d Sigma_v = Eigen::Matrix2d::Identity() * 1e-5;  ///< Cartesian noise of the run
	Eigen::Matrix3d Sigma_0 = Eigen::Matrix3d::Zero();
	double std_range = 0, std_yaw = 0;  ///< equivalent range-bearing stds
};

/** datasets/highway.rawlog with the noise of datasets/highway_scenario.ini (read once). */
const TRun& highwayRun();
/** A scenario INI of config/ simulated in memory (sim::buildGroundTruth + simulateMeasurements),
 * cached by (file, landmarks override, seed). landmarks < 0: as in the file. */
const TRun& simulatedRun(const std::string& configFile, int landmarks, unsigned noiseSeed);

/** The dynamic EKF as the apps run it on the highway: Cartesian model, Sigma_v of the run,
 * Sigma_0, motion noise from the action, no smoothing, K = 1, kfEKFNaive. */
void configureDynamic(dynslam::CDynamicKFSLAM2D& f, const Eigen::Matrix2d& Sigma_v,
                      const Eigen::Matrix3d& Sigma_0, bool sparse);
/** MRPT's static EKF and the dynamic EKF set up to do the same computation (as in
 * tests/ekf/test_vs_mrpt.cpp): range-bearing model with MRPT's float stds, Sigma_0 = 0, the
 * prediction skipped while the map is empty, kfEKFNaive. */
void configureAlike(mrpt::slam::CRangeBearingKFSLAM2D& rb, dynslam::CDynamicKFSLAM2D& dyn,
                    double std_range, double std_yaw, bool sparse);

/** Peak resident set size of this process [kB] (getrusage ru_maxrss). */
long peakRssKb();
/** Current resident set size [kB] (/proc/self/statm), -1 if unavailable. */
long currentRssKb();
}  // namespace dynslam_bench
