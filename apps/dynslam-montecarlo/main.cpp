/** dynslam-montecarlo: the Monte Carlo experiment of the paper (Table I).
 * All logic is in dynslam::apps::CMonteCarloApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CMonteCarloApp.h>
#include <mrpt/core/exceptions.h>

#include <iostream>

int main(int argc, const char** argv)
{
	try
	{
		dynslam::apps::CMonteCarloApp app;
		if (!app.initialize(argc, argv)) return 0;
		app.run();
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-montecarlo: error: " << mrpt::exception_to_str(e) << "\n";
		return 1;
	}
}
