#!/usr/bin/env bash
# Configures and builds dynslam in build/ (Release, all cores). Usage: scripts/build.sh [extra cmake args]
# DYNSLAM_BUILD_TARGETS="t1 t2": build only these targets (and what they need); default: all.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${DYNSLAM_BUILD_DIR:-$ROOT/build}"
# ccache: hash paths relative to the checkout, so another clone reuses the cache.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}"
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
targets=()
for t in ${DYNSLAM_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$BUILD" -j"$(nproc)" "${targets[@]}"
