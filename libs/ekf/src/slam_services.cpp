/** The default definitions of slam_services.h: the classes, linked in. Keep this file to these
 * two functions (a program that defines them itself must not need anything else from here). */
#include <dynslam/ekf/CJcbbUpdateEngine.h>
#include <dynslam/ekf/mrpt_static_association.h>
#include <dynslam/ekf/slam_services.h>

namespace dynslam
{
estimator::StaticAssociationFn slamStaticAssociation(const estimator::TUnknownIdParams& p)
{
	return makeMrptStaticAssociation(p);
}

std::unique_ptr<estimator::IUpdateEngine> slamJcbbEngine(double confidence)
{
	return std::make_unique<CJcbbUpdateEngine>(confidence);
}
}  // namespace dynslam
