#pragma once
/** --benchmark_format=csv / --benchmark_out_format=csv for benchmarks with different counters
 * (issue 30, item 11). Google Benchmark's CSVReporter writes its header from the counters of
 * the first benchmark it reports and aborts ("All counters must be present in each run") when
 * a later one has another counter. This reporter keeps every run and hands them to the
 * CSVReporter once, at the end: the header then has the union of the counters, and a run
 * without a counter gets an empty cell (CSVReporter's own rule). The rows come out at the end
 * instead of one benchmark at a time. */
#include <benchmark/benchmark.h>

#include <vector>

namespace dynslam_bench
{
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#endif
class CUnionCsvReporter : public benchmark::CSVReporter
{
public:
	void ReportRuns(const std::vector<Run>& reports) override
	{
		m_runs.insert(m_runs.end(), reports.begin(), reports.end());
	}
	void Finalize() override
	{
		if (!m_runs.empty()) benchmark::CSVReporter::ReportRuns(m_runs);
		m_runs.clear();
		benchmark::CSVReporter::Finalize();
	}

private:
	std::vector<Run> m_runs;
};
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
}  // namespace dynslam_bench
