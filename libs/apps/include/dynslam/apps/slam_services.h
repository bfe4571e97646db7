#pragma once
/** @file slam_services.h
 * The apps library's only use of MRPT's slam library (libmrpt-slam): the static baselines
 * static_all / static_landmarks_only (CStaticBaselineBackend, MRPT's CRangeBearingKFSLAM2D),
 * behind two functions that makeBackend() and collectFinalEstimates() call instead of the
 * class. Defined in libdynslam_apps (slam_services.cpp, nothing else in that object file); a
 * program may define both itself, as dynslam-montecarlo does to start without libmrpt-slam
 * (see dynslam/ekf/slam_services.h of the EKF for the mechanism). */
#include <dynslam/common/ISlamBackend.h>
#include <mrpt/config/CConfigFileBase.h>

#include <Eigen/Core>
#include <memory>
#include <ostream>
#include <string>

namespace dynslam::apps
{
/** makeBackend() for kind static_all or static_landmarks_only: a CStaticBaselineBackend
 * configured from [RangeBearingKFSLAM]; its options written to optionsDump if given. */
std::unique_ptr<ISlamBackend> slamStaticBaseline(const std::string& kind,
                                                 const mrpt::config::CConfigFileBase& ini,
                                                 std::ostream* optionsDump);
/** If backend is a CStaticBaselineBackend: its landmarksJointCov() into C, true; else false. */
bool slamStaticBaselineJointCov(const ISlamBackend& backend, Eigen::MatrixXd& C);
}  // namespace dynslam::apps
