#include <dynslam/ekf/ekf_registries.h>
#include <dynslam/ekf/slam_services.h>

namespace dynslam
{
const estimator::CUpdateEngineRegistry& ekfUpdateEngines()
{
	static const estimator::CUpdateEngineRegistry r = []
	{
		estimator::CUpdateEngineRegistry g = estimator::updateEngines();
		g.add("jcbb",
		      [](const estimator::TUpdateEngineParams& p)
		      { return slamJcbbEngine(p.gate_probability); },
		      {true, true});
		return g;
	}();
	return r;
}
}  // namespace dynslam
