/** dynslam-run: runs a back-end (default: the dynamic EKF) on a rawlog.
 * All logic is in dynslam::apps::CRunApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CRunApp.h>
#include <mrpt/core/exceptions.h>

#include <iostream>

int main(int argc, const char** argv)
{
	try
	{
		dynslam::apps::CRunApp app;
		if (!app.initialize(argc, argv)) return 0;
		app.run();
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-run: error: " << mrpt::exception_to_str(e) << "\n";
		return 1;
	}
}
