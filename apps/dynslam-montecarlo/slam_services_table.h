#pragma once
/** @file slam_services_table.h
 * What the module libdynslam_slam_services.so hands to dynslam-montecarlo: the four functions
 * of dynslam/ekf/slam_services.h (EKF) and dynslam/apps/slam_services.h (static baselines), i.e.
 * every use of MRPT's slam library, compiled and linked in the module. The executable defines
 * the same four functions itself (slam_services_lazy.cpp) and loads the module on first use,
 * so a sweep of the EKF never loads libmrpt-slam and its ~125 dependent libraries
 * (doc/results/performance.md section 14). */
#include <dynslam/apps/slam_services.h>
#include <dynslam/ekf/slam_services.h>

namespace dynslam::apps
{
struct TSlamServicesTable
{
	int version = 1;  ///< kSlamServicesVersion of the module
	decltype(&dynslam::slamStaticAssociation) staticAssociation = nullptr;
	decltype(&dynslam::slamJcbbEngine) jcbbEngine = nullptr;
	decltype(&slamStaticBaseline) staticBaseline = nullptr;
	decltype(&slamStaticBaselineJointCov) staticBaselineJointCov = nullptr;
};
/** Bumped whenever the table or the types crossing it change. */
constexpr int kSlamServicesVersion = 1;
constexpr const char* kSlamServicesModule = "libdynslam_slam_services.so";
constexpr const char* kSlamServicesEntry = "dynslam_slam_services";
}  // namespace dynslam::apps
