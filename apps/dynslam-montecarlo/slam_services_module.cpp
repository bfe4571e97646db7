/** The module libdynslam_slam_services.so (slam_services_table.h): the default, linked-in
 * definitions of the four functions, from libdynslam_ekf and libdynslam_apps, behind one C
 * entry point. The static libraries' symbols are not exported (-Wl,--exclude-libs,ALL): the
 * module's copies of them stay its own. */
#include "slam_services_table.h"

extern "C" __attribute__((visibility("default"))) const dynslam::apps::TSlamServicesTable*
dynslam_slam_services()
{
	static const dynslam::apps::TSlamServicesTable t{
	    dynslam::apps::kSlamServicesVersion, &dynslam::slamStaticAssociation,
	    &dynslam::slamJcbbEngine, &dynslam::apps::slamStaticBaseline,
	    &dynslam::apps::slamStaticBaselineJointCov};
	return &t;
}
