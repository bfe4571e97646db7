/** The default definitions of slam_services.h: the classes, linked in. Keep this file to these
 * two functions (a program that defines them itself must not need anything else from here). */
#include <dynslam/CJcbbUpdateEngine.h>
#include <dynslam/mrpt_static_association.h>
#include <dynslam/slam_services.h>

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
