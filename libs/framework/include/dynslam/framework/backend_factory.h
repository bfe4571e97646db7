#pragma once
/** @file backend_factory.h
 * Creates a back-end of the framework by kind (doc/backends.md): alg1 (CAlg1Backend, the
 * EKF-equivalent Alg. 1), vdo, dynaslam2, cubeslam, clusterslam_decoupled,
 * clusterslam_semidecoupled (CWindowBackend). */
#include <dynslam/common/ISlamBackend.h>
#include <dynslam/framework/TBackendOptions.h>
#include <mrpt/config/CConfigFileBase.h>

#include <memory>
#include <string>

namespace dynslam::framework
{
/** The options: the kind's defaults, overridden by [section] (which may omit `backend`; if it
 * names another kind, std::invalid_argument). The model comes from [model_section]. */
std::unique_ptr<ISlamBackend> makeBackend(const std::string& kind,
                                          const mrpt::config::CConfigFileBase& ini,
                                          const std::string& section);
/** From ready options (opts.backend selects the class). */
std::unique_ptr<ISlamBackend> makeBackend(const TBackendOptions& opts);
}  // namespace dynslam::framework
