/** dynslam-compare: static EKF-SLAM vs. the dynamic EKF on one rawlog.
 * All logic is in dynslam::apps::CCompareApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CCompareApp.h>
#include <mrpt/core/exceptions.h>

#include <iostream>

int main(int argc, const char** argv)
{
	try
	{
		dynslam::apps::CCompareApp app;
		if (!app.initialize(argc, argv)) return 0;
		app.run();
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-compare: error: " << mrpt::exception_to_str(e) << "\n";
		return 1;
	}
}
