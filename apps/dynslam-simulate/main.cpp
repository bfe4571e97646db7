/** dynslam-simulate: writes a scenario as an MRPT rawlog with ground truth.
 * All logic is in dynslam::sim::CSimulateApp (libs/sim); see doc/simulator.md. */
#include <dynslam/apps/app_main.h>
#include <dynslam/sim/CSimulateApp.h>

int main(int argc, const char** argv)
{
	return dynslam::apps::runMain("dynslam-simulate",
	                              [&]
	                              {
		                              dynslam::sim::CSimulateApp app;
		                              if (!app.initialize(argc, argv)) return 0;
		                              app.run();
		                              return 0;
	                              });
}
