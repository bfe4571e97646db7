/** dynslam-bench main: Google Benchmark's, plus --peak-memory (one default highway run, then
 * the process's peak resident set size from getrusage). Run it through scripts/bench.sh. */
#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>

#include "bench_setup.h"

using namespace dynslam_bench;

int main(int argc, char** argv)
{
	for (int i = 1; i < argc; ++i)
		if (std::strcmp(argv[i], "--peak-memory") == 0)
		{
			const long before = peakRssKb();
			const TRun& run = highwayRun();
			const long loaded = peakRssKb();
			dynslam::CDynamicKFSLAM2D f;
			configureDynamic(f, run.Sigma_v, run.Sigma_0, true);
			for (size_t k = 0; k < run.actions.size(); ++k)
				f.processActionObservation(run.actions[k], run.frames[k]);
			std::cout << "peak_rss_kB_at_start " << before << "\npeak_rss_kB_after_loading_rawlog "
			          << loaded << "\npeak_rss_kB_after_highway_run " << peakRssKb()
			          << "\nstate_dim " << f.fullMean().size() << "\n";
			return 0;
		}
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	benchmark::RunSpecifiedBenchmarks();
	benchmark::Shutdown();
	return 0;
}
