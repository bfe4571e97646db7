#pragma once
/** @file peak_memory.h
 * The process's peak memory (dynslam-run's metrics.csv column peak_rss_mb). */

namespace dynslam::eval
{
/** Peak resident set size of this process so far, in MiB (2^20 bytes): getrusage(RUSAGE_SELF)
 * ru_maxrss (kilobytes on Linux). NaN where the system does not report it. */
double peakRssMb();
}  // namespace dynslam::eval
