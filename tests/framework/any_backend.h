#pragma once
/** Every back-end of the project behind ISlamBackend, from one INI text: "ekf"
 * (CDynamicKFSLAM2D, [DynamicKFSLAM]) or a framework kind (makeBackend, [Framework]). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <dynslam/framework/backend_factory.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <memory>
#include <string>
#include <vector>

namespace dynslam_test
{
inline std::unique_ptr<dynslam::ISlamBackend> anyBackend(const std::string& kind,
                                                         const std::string& ini)
{
	mrpt::config::CConfigFileMemory c(ini);
	if (kind == "ekf")
	{
		auto e = std::make_unique<dynslam::CDynamicKFSLAM2D>();
		e->setMinLoggingLevel(mrpt::system::LVL_ERROR);
		e->loadOptions(c);
		return e;
	}
	return dynslam::framework::makeBackend(kind, c, "Framework");
}

/** The EKF, Alg. 1 and every windowed configuration. */
inline std::vector<std::string> allBackendKinds()
{
	std::vector<std::string> k{"ekf"};
	for (const auto& f : dynslam::framework::backendKinds()) k.push_back(f);
	return k;
}
}  // namespace dynslam_test
