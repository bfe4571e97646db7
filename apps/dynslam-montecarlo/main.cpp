/** dynslam-montecarlo: the Monte Carlo experiment of the paper (Table I).
 * All logic is in dynslam::apps::CMonteCarloApp (libs/apps); see doc/apps.md. */
#include <dynslam/apps/CMonteCarloApp.h>
#include <dynslam/apps/app_main.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

int main(int argc, const char** argv)
{
#if defined(__GLIBC__)
	// A sweep runs hundreds of filters one after the other per thread: keep freed memory in the
	// process (blocks up to 32 MiB from the heap, no trimming below 256 MiB free) instead of
	// mapping fresh pages from the kernel for every run (doc/results/performance.md, section 10:
	// 53,000 -> 10,000 page faults, system time 0.15 -> 0.05 s for the 225 runs).
	mallopt(M_MMAP_THRESHOLD, 32 << 20);
	mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
	return dynslam::apps::runMain("dynslam-montecarlo",
	                              [&]
	                              {
		                              dynslam::apps::CMonteCarloApp app;
		                              if (!app.initialize(argc, argv)) return 0;
		                              app.run();
		                              return 0;
	                              });
}
