/** dynslam-compare: static EKF-SLAM vs. the dynamic EKF on one rawlog.
 * All logic is in dynslam::apps::CCompareApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CCompareApp.h>
#include <dynslam/apps/app_main.h>

int main(int argc, const char** argv)
{
	return dynslam::apps::runMain("dynslam-compare",
	                              [&]
	                              {
		                              dynslam::apps::CCompareApp app;
		                              if (!app.initialize(argc, argv)) return 0;
		                              app.run();
		                              return 0;
	                              });
}
