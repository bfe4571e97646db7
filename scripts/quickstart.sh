#!/usr/bin/env bash
# The main job: installs what is missing, builds what dynslam-compare needs (only that target:
# scripts/test.sh builds the rest), and runs the highway comparison (static EKF-SLAM vs.
# dynamic EKF-SLAM) on the shipped default rawlog.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
DYNSLAM_BUILD_TARGETS=dynslam-compare "$ROOT/scripts/build.sh"
cd "$ROOT"
"${DYNSLAM_BUILD_DIR:-$ROOT/build}/apps/dynslam-compare/dynslam-compare" "$@"
