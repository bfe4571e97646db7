#pragma once
/** @file run_records.h
 * Lossless text records of scored Monte Carlo runs (dynslam-montecarlo --shard writes them,
 * --merge reads them back and builds the tables; doc/apps.md). Every double is written in
 * C's hexadecimal floating format (%a), so a record reads back bit for bit and merged tables
 * equal the single-machine tables byte for byte. Format (version 1), one item per line:
 *
 *   # comment lines
 *   dynslam-montecarlo-runs 1
 *   sweep KEY=VALUE ...                  the sweep (levels, runs, seed, backend, scenario, ...)
 *   run LEVEL RUN SEED STEPS
 *   rmse NAME x y theta n_xy n_theta     NAME = ego | static_map
 *   scalars ate ego_skipped landmarks_missing landmarks_unmatched object_estimates_unmatched
 *           ms_per_step
 *   object ID TRANSLATION_ONLY FEATURES_MISSING POSES_SKIPPED  then "rmse features ..." and
 *           "rmse poses ..." lines
 *   samples NAME SKIPPED N key value dof ...   NAME = ego | landmarks | map | nis | object:ID
 *   map_joint_cov 0|1
 *   end
 * Readers throw std::runtime_error naming the file and line on anything else. */
#include <dynslam/eval/consistency.h>
#include <dynslam/eval/metrics.h>

#include <cstdint>
#include <istream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace dynslam::eval
{
struct TRunRecord
{
	std::string level;
	int run = 0;
	uint64_t seed = 0;
	size_t steps = 0;
	TRunMetrics metrics;
	TRunConsistency consistency;
};

struct TRunRecordFile
{
	std::map<std::string, std::string> sweep;  ///< the "sweep" line's KEY=VALUE pairs
	std::vector<TRunRecord> runs;
};

void writeRunRecords(std::ostream& os, const TRunRecordFile& f);
/** `name` is used in error messages. */
TRunRecordFile readRunRecords(std::istream& is, const std::string& name);
}  // namespace dynslam::eval
