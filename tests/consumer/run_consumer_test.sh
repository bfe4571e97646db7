#!/usr/bin/env bash
# Installs dynslam from the build tree into a temporary prefix, then configures, builds and runs
# a tiny external project that finds it with find_package(dynslam).
set -euo pipefail
BUILD="$1"; WORK="$2"
rm -rf "$WORK"; mkdir -p "$WORK"
cmake --install "$BUILD" --prefix "$WORK/prefix" >/dev/null
# Both external projects (consumer_projects.sh); project_estimator uses the estimator libraries
# without apps: no OpenCV looked for (project_estimator/CMakeLists.txt). cmake's output hidden.
source "$(dirname "$0")/consumer_projects.sh"
cmake_quiet() { if [ "$1" = cmake ]; then "$@" >/dev/null; else "$@"; fi; }
build_consumers "$WORK/prefix" "$WORK" cmake_quiet
echo "consumer: find_package(dynslam COMPONENTS <all but apps>) without OpenCV ok"
# The installed dynslam-montecarlo finds its module libdynslam_slam_services.so (MRPT's static
# filter; doc/results/performance.md section 14) through its RUNPATH $ORIGIN/../lib: one static run.
MC="$WORK/prefix/bin/dynslam-montecarlo"
if [ -x "$MC" ]; then
  CFG="$WORK/prefix/share/dynslam/config"
  sed -e "s#^scenario *= *#scenario = $CFG/#" -e 's/^backend *=.*/backend = static_all/' \
    -e "s#^@include  *\([^/]\)#@include $CFG/\1#" \
    "$CFG/montecarlo.ini" > "$WORK/mc_static.ini"
  printf '\n[RangeBearingKFSLAM]\nstd_sensor_range = 0.01\nstd_sensor_yaw_deg = 0.0573\n' \
    >> "$WORK/mc_static.ini"
  "$MC" -c "$WORK/mc_static.ini" --runs 1 --levels w1v1 --threads 1 --no-figures -q \
    -o "$WORK/mc_out" >/dev/null
  test -s "$WORK/mc_out/table1.csv"
  echo "consumer: installed dynslam-montecarlo with static_all ok"
fi
