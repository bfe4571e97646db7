#!/usr/bin/env bash
# The test command: installs what is missing, builds from scratch if needed, runs ctest.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
"$ROOT/scripts/build.sh"
cd "${DYNSLAM_BUILD_DIR:-$ROOT/build}"
ctest --output-on-failure -j"$(nproc)" --timeout 900
