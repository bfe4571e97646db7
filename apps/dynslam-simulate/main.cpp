/** dynslam-simulate: writes a scenario as an MRPT rawlog with ground truth.
 * All logic is in dynslam::sim::CSimulateApp (libs/sim); see doc/simulator.md. */
#include <dynslam/sim/CSimulateApp.h>

#include <iostream>

int main(int argc, const char** argv)
{
	try
	{
		dynslam::sim::CSimulateApp app;
		if (!app.initialize(argc, argv)) return 0;
		app.run();
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-simulate: " << e.what() << "\n";
		return 1;
	}
}
