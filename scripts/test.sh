#!/usr/bin/env bash
# The test command: installs what is missing, builds from scratch if needed, runs ctest.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
DYNSLAM_UNITY="${DYNSLAM_UNITY:-OFF}" "$ROOT/scripts/build.sh"  # one source per compile
cd "${DYNSLAM_BUILD_DIR:-$ROOT/build}"
ctest --output-on-failure -j"$(nproc)" --timeout 900
