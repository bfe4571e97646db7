/** dynslam-montecarlo's own definitions of the functions of dynslam/ekf/slam_services.h and
 * dynslam/apps/slam_services.h: the module libdynslam_slam_services.so (slam_services_table.h)
 * is loaded on the first call, so the executable itself does not link libmrpt-slam (checked
 * by the test MonteCarloSlamModule.ExecutableDoesNotNeedLibmrptSlam). Being defined here, the
 * linker never takes the libraries' definitions (slam_services.cpp.o) out of their archives. */
#include <dlfcn.h>

#include <atomic>
#include <stdexcept>
#include <string>

#include "slam_services_table.h"

namespace dynslam::apps
{
namespace
{
std::atomic<bool> g_loaded{false};

const TSlamServicesTable* loadModule()
{
	const std::string what =
	    std::string(
	        "dynslam-montecarlo: MRPT's static filter and data association (back-ends "
	        "static_all / static_landmarks_only, outlier_method = jcbb, feature_labels = "
	        "classify) are in the module ") +
	    kSlamServicesModule;
	void* h = dlopen(kSlamServicesModule, RTLD_NOW | RTLD_LOCAL);
	if (!h) throw std::runtime_error(what + ", which could not be loaded: " + dlerror());
	using Entry = const TSlamServicesTable* (*)();
	const auto entry = reinterpret_cast<Entry>(dlsym(h, kSlamServicesEntry));
	const TSlamServicesTable* t = entry ? entry() : nullptr;
	if (!t || t->version != kSlamServicesVersion)
		throw std::runtime_error(what + ": not the version this executable was built with");
	g_loaded = true;
	return t;
}

const TSlamServicesTable& module()
{
	static const TSlamServicesTable* t = loadModule();  // thread-safe, retried after a throw
	return *t;
}
}  // namespace

std::unique_ptr<ISlamBackend> slamStaticBaseline(const std::string& kind,
                                                 const mrpt::config::CConfigFileBase& ini,
                                                 std::ostream* optionsDump)
{
	return module().staticBaseline(kind, ini, optionsDump);
}

bool slamStaticBaselineJointCov(const ISlamBackend& backend, Eigen::MatrixXd& C)
{
	// No static baseline exists before the module is loaded: do not load it to find that out.
	return g_loaded && module().staticBaselineJointCov(backend, C);
}
}  // namespace dynslam::apps

namespace dynslam
{
estimator::StaticAssociationFn slamStaticAssociation(const estimator::TUnknownIdParams& p)
{
	return apps::module().staticAssociation(p);
}

std::unique_ptr<estimator::IUpdateEngine> slamJcbbEngine(double confidence)
{
	return apps::module().jcbbEngine(confidence);
}
}  // namespace dynslam
