/** dynslam-montecarlo: the Monte Carlo experiment of the paper (Table I).
 * All logic is in dynslam::apps::CMonteCarloApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CMonteCarloApp.h>
#include <dynslam/apps/app_main.h>

int main(int argc, const char** argv)
{
	return dynslam::apps::runMain("dynslam-montecarlo",
	                              [&]
	                              {
		                              dynslam::apps::CMonteCarloApp app;
		                              if (!app.initialize(argc, argv)) return 0;
		                              app.run();
		                              return 0;
	                              });
}
