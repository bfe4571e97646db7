/** dynslam-bench main: Google Benchmark's, plus --peak-memory (one default highway run, then
 * the process's peak resident set size from getrusage) and --isa=sse2|avx2 (the kernel variant,
 * dynslam/core/kernels.h; default: DYNSLAM_ISA, else the best the CPU runs; reported in the context
 * as dynslam_isa). Run it through scripts/bench.sh. CSV output (--benchmark_format=csv,
 * --benchmark_out_format=csv) has the union of the counters of all benchmarks (csv_reporter.h). */
#include <benchmark/benchmark.h>
#include <dynslam/core/kernels.h>

#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>

#include "bench_setup.h"
#include "csv_reporter.h"

using namespace dynslam_bench;

namespace
{
/** Takes --isa=NAME out of argv (Google Benchmark rejects unknown flags) and selects it. */
bool selectIsa(int& argc, char** argv)
{
	int out = 1;
	for (int i = 1; i < argc; ++i)
	{
		const std::string a = argv[i];
		if (a.rfind("--isa=", 0) != 0)
		{
			argv[out++] = argv[i];
			continue;
		}
		try
		{
			dynslam::kernels::setActiveIsa(dynslam::kernels::parseIsa(a.substr(6)));
		}
		catch (const std::runtime_error& e)
		{
			std::cerr << "dynslam-bench: " << a << ": " << e.what() << "\n";
			return false;
		}
	}
	argc = out;
	argv[out] = nullptr;
	return true;
}
}  // namespace

int main(int argc, char** argv)
{
	if (!selectIsa(argc, argv)) return 1;
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
	benchmark::AddCustomContext("dynslam_isa",
	                            dynslam::kernels::isaName(dynslam::kernels::activeIsa()));
	// CSV: the union of the counters of all benchmarks (csv_reporter.h).
	bool csvDisplay = false, csvFile = false, outFile = false;
	for (int i = 1; i < argc; ++i)
	{
		const std::string a = argv[i];
		csvDisplay = csvDisplay || a == "--benchmark_format=csv";
		csvFile = csvFile || a == "--benchmark_out_format=csv";
		outFile = outFile || a.rfind("--benchmark_out=", 0) == 0;
	}
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	CUnionCsvReporter display, file;
	benchmark::RunSpecifiedBenchmarks(csvDisplay ? &display : nullptr,
	                                  csvFile && outFile ? &file : nullptr);
	benchmark::Shutdown();
	return 0;
}
