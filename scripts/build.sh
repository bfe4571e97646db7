#!/usr/bin/env bash
# Configures and builds dynslam in build/ (Release, all cores). Usage: scripts/build.sh [extra cmake args]
# DYNSLAM_BUILD_TARGETS="t1 t2": build only these targets (and what they need); default: all.
# DYNSLAM_UNITY=ON|OFF: sets CMake's CMAKE_UNITY_BUILD (several sources per compile: less CPU
# for a cold build; scripts/quickstart.sh uses it in a new build folder, scripts/test.sh sets OFF);
# unset: the build folder keeps its setting (OFF in a new one).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${DYNSLAM_BUILD_DIR:-$ROOT/build}"
# ccache: hash paths relative to the checkout, so another clone reuses the cache.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}"
unity=()
[ -z "${DYNSLAM_UNITY:-}" ] || unity=(-DCMAKE_UNITY_BUILD="$DYNSLAM_UNITY")
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release "${unity[@]}" "$@" >/dev/null
targets=()
for t in ${DYNSLAM_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$BUILD" -j"$(nproc)" "${targets[@]}"
