/** dynslam-compare's filter row `default`: the INI with the default profile's keys of
 * [DynamicKFSLAM] and of the module sections (doc/configuration.md "Profiles"). */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/common/config_include.h>
#include <dynslam/common/model_keys.h>

namespace dynslam::apps
{
const mrpt::config::CConfigFileBase& CCompareApp::paramsFor(
    const std::string& filter, const mrpt::config::CConfigFileMemory& base)
{
	if (filter != "default") return base;
	m_defaultParams = std::make_unique<mrpt::config::CConfigFileMemory>();
	std::vector<std::string> sections{kCoreSection};
	for (const std::string& s : moduleSections()) sections.push_back(s);
	config::overlayProfile(base, defaultProfile, sections, *m_defaultParams);
	return *m_defaultParams;
}
}  // namespace dynslam::apps
