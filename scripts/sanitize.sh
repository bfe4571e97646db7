#!/usr/bin/env bash
# Builds the whole test suite with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DDYNSLAM_SANITIZE=ON, RelWithDebInfo) in build-sanitize/ and runs ctest there.
# Not part of ctest (too slow for CI); the clean result is recorded in doc/robustness.md.
# Usage: scripts/sanitize.sh [extra cmake args, e.g. -DDYNSLAM_TEST_AREAS="core;ekf;hardening"]
# Environment: DYNSLAM_SANITIZE_BUILD_DIR (default build-sanitize), JOBS (default 2),
# SANITIZE_TARGETS (default all).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${DYNSLAM_SANITIZE_BUILD_DIR:-$ROOT/build-sanitize}"
JOBS="${JOBS:-2}"
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDYNSLAM_SANITIZE=ON \
  -DDYNSLAM_BUILD_BENCH=OFF -DDYNSLAM_BUILD_APPS=ON "$@" >/dev/null
# SANITIZE_TARGETS: build only these (e.g. "core_tests ekf_tests hardening_tests" together with
# -DDYNSLAM_TEST_AREAS="core;ekf;hardening"); default: everything.
t0=$SECONDS
# shellcheck disable=SC2086
cmake --build "$BUILD" -j"$JOBS" --target ${SANITIZE_TARGETS:-all}
echo "sanitize: build took $((SECONDS - t0)) s wall; CPU user/sys so far (children line):"
times
# detect_leaks: MRPT's class registry keeps singletons alive at exit; leaks are reported but
# only the errors below fail the run. halt_on_error: the first ASan/UBSan report fails the test.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:halt_on_error=1:abort_on_error=1:detect_stack_use_after_return=1:max_allocation_size_mb=3072}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# The soak test runs its short version here (ASan is ~3x slower).
export DYNSLAM_SOAK_STEPS="${DYNSLAM_SOAK_STEPS:-5000}"
# ConsumerFindPackage builds an external project against the installed (instrumented, static)
# libraries: its fresh CMake configure takes these as its initial flags, so it links.
export CXXFLAGS="${CXXFLAGS:-} -fsanitize=address,undefined -fno-omit-frame-pointer"
export LDFLAGS="${LDFLAGS:-} -fsanitize=address,undefined"
cd "$BUILD"
t0=$SECONDS
rc=0
ctest --output-on-failure -j"$JOBS" --timeout 1800 || rc=$?
echo "sanitize: ctest took $((SECONDS - t0)) s (exit $rc)"
exit "$rc"
