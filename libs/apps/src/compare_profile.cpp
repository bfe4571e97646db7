/** dynslam-compare's filter row `default`: the INI with the default profile's
 * [DynamicKFSLAM] keys (doc/configuration.md "Profiles"). */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/config_include.h>

namespace dynslam::apps
{
const mrpt::config::CConfigFileBase& CCompareApp::paramsFor(
    const std::string& filter, const mrpt::config::CConfigFileMemory& base)
{
	if (filter != "default") return base;
	m_defaultParams = std::make_unique<mrpt::config::CConfigFileMemory>();
	config::overlayProfile(base, defaultProfile, "DynamicKFSLAM", *m_defaultParams);
	return *m_defaultParams;
}
}  // namespace dynslam::apps
