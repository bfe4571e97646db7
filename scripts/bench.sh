#!/usr/bin/env bash
# Builds and runs dynslam-bench (Release, build-bench/ unless DYNSLAM_BENCH_BUILD_DIR is set),
# with repetitions, and prints the medians, the side-by-side ratios and the machine.
# Usage: scripts/bench.sh [repetitions, default 5] [extra benchmark flags, e.g. --benchmark_filter=Highway]
# Results: build-bench/bench.json (all repetitions) and build-bench/bench-summary.md.
# DYNSLAM_BENCH_CMAKE_ARGS: extra cmake arguments, e.g. the CPU-specific build of
# doc/results/performance.md:  DYNSLAM_BENCH_BUILD_DIR=build-bench-native \
#   DYNSLAM_BENCH_CMAKE_ARGS=-DDYNSLAM_NATIVE=ON scripts/bench.sh 3
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${DYNSLAM_BENCH_BUILD_DIR:-$ROOT/build-bench}"
REPS="${1:-5}"
shift || true
# shellcheck disable=SC2086
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release ${DYNSLAM_BENCH_CMAKE_ARGS:-} >/dev/null
cmake --build "$BUILD" -j"${JOBS:-2}" --target dynslam-bench
BIN="$BUILD/bench/dynslam-bench"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg)"
"$BIN" --peak-memory | tee "$BUILD/bench-memory.txt"
"$BIN" --benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=true \
  --benchmark_out="$BUILD/bench.json" --benchmark_out_format=json "$@"
python3 "$ROOT/scripts/bench_summary.py" "$BUILD/bench.json" | tee "$BUILD/bench-summary.md"
