#!/usr/bin/env bash
# The main job: installs what is missing, builds what dynslam-compare needs (only that target:
# scripts/test.sh builds the rest), and runs the highway comparison (static EKF-SLAM vs.
# dynamic EKF-SLAM) on the shipped default rawlog.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install_deps.sh"
# A new build folder is a unity build (doc/building.md "Unity build": about half the CPU of one
# source per compile); an existing one keeps its setting (scripts/test.sh's: OFF).
[ -f "${DYNSLAM_BUILD_DIR:-$ROOT/build}/CMakeCache.txt" ] || export DYNSLAM_UNITY="${DYNSLAM_UNITY:-ON}"
DYNSLAM_BUILD_TARGETS=dynslam-compare "$ROOT/scripts/build.sh"
cd "$ROOT"
"${DYNSLAM_BUILD_DIR:-$ROOT/build}/apps/dynslam-compare/dynslam-compare" "$@"
