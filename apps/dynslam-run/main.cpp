/** dynslam-run: runs a back-end (default: the dynamic EKF) on a rawlog.
 * All logic is in dynslam::apps::CRunApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CRunApp.h>
#include <dynslam/apps/app_main.h>

int main(int argc, const char** argv)
{
	return dynslam::apps::runMain("dynslam-run",
	                              [&]
	                              {
		                              dynslam::apps::CRunApp app;
		                              if (!app.initialize(argc, argv)) return 0;
		                              app.run();
		                              return 0;
	                              });
}
