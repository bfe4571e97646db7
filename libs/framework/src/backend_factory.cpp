#include <dynslam/framework/CAlg1Backend.h>
#include <dynslam/framework/CWindowBackend.h>
#include <dynslam/framework/backend_factory.h>

#include <stdexcept>

namespace dynslam::framework
{
std::unique_ptr<ISlamBackend> makeBackend(const TBackendOptions& opts)
{
	if (opts.backend == "alg1") return std::make_unique<CAlg1Backend>(opts);
	return std::make_unique<CWindowBackend>(opts);
}

std::unique_ptr<ISlamBackend> makeBackend(const std::string& kind,
                                          const mrpt::config::CConfigFileBase& ini,
                                          const std::string& section)
{
	TBackendOptions o = defaultBackendOptions(kind);
	o.loadFromConfigFile(ini, section);
	if (o.backend != kind)
		throw std::invalid_argument("[" + section + "] backend = " + o.backend +
		                            " differs from the requested kind " + kind);
	return makeBackend(o);
}
}  // namespace dynslam::framework
