#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang, ASan and UBSan in build-fuzz/ and runs each
# for a fixed time from the seed corpus. Usage: scripts/fuzz.sh [seconds per target, default 300]
# Environment: DYNSLAM_FUZZ_BUILD_DIR (default build-fuzz), JOBS (default 2), FUZZ_TARGETS
# (default "rawlog ini").
# A crash leaves crash-*/oom-*/leak-* reproducers in build-fuzz/artifacts/ and fails the script.
# The same entry points run for a fixed count in ctest (tests/hardening, fuzz_replay).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${DYNSLAM_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
SECONDS_PER_TARGET="${1:-300}"
JOBS="${JOBS:-2}"
FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -g"
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDYNSLAM_FUZZ=ON -DDYNSLAM_BUILD_TESTS=OFF -DDYNSLAM_BUILD_APPS=OFF -DDYNSLAM_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="$FLAGS" >/dev/null
cmake --build "$BUILD" -j"$JOBS" --target dynslam-fuzz-rawlog dynslam-fuzz-ini dynslam-fuzz-seeds
mkdir -p "$BUILD/corpus/rawlog" "$BUILD/corpus/ini" "$BUILD/artifacts"
"$BUILD/fuzz/dynslam-fuzz-seeds" "$BUILD/corpus/rawlog" "$BUILD/corpus/ini"
# detect_leaks=0: MRPT's class registry singletons; malloc_limit_mb: a corrupt length field that
# asks for > 2 GB is reported as an OOM finding rather than swapping the machine.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
for t in ${FUZZ_TARGETS:-rawlog ini}; do
  echo "== dynslam-fuzz-$t for ${SECONDS_PER_TARGET} s"
  rc=0
  "$BUILD/fuzz/dynslam-fuzz-$t" "$BUILD/corpus/$t" -max_total_time="$SECONDS_PER_TARGET" \
    -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
    -artifact_prefix="$BUILD/artifacts/$t-" > "$BUILD/fuzz-$t.log" 2>&1 || rc=$?
  # The rawlog target forks a child per input that runs MRPT's deserializer alone; a child that
  # hits libFuzzer's -malloc_limit_mb or a sanitizer inside MRPT prints its own report (and
  # stat:: lines, and may write an artifact) and the input is skipped. The verdict is the exit
  # code of the fuzzer process; its own statistics are the last stat:: block.
  grep -E "^#[0-9]+[[:space:]]+(INITED|DONE)" "$BUILD/fuzz-$t.log" | sed -n '1p;$p' || true
  grep -E "^stat::" "$BUILD/fuzz-$t.log" | tail -n 5 || true
  echo "reports from forked MRPT-only children (inputs skipped): $(grep -c "^==[0-9]*== ERROR" "$BUILD/fuzz-$t.log" || true)"
  if [ "$rc" -ne 0 ]; then
    grep -E "ERROR|SUMMARY" "$BUILD/fuzz-$t.log" | tail -n 5
    echo "dynslam-fuzz-$t failed (exit $rc), see $BUILD/fuzz-$t.log"
    exit "$rc"
  fi
done
echo "fuzz: no crash"
