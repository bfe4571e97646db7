#!/usr/bin/env bash
# Installs dynslam from the build tree into a temporary prefix, then configures, builds and runs
# a tiny external project that finds it with find_package(dynslam).
set -euo pipefail
BUILD="$1"; SRC="$2"; WORK="$3"
rm -rf "$WORK"; mkdir -p "$WORK"
cmake --install "$BUILD" --prefix "$WORK/prefix" >/dev/null
cmake -S "$SRC" -B "$WORK/build" -DCMAKE_PREFIX_PATH="$WORK/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$WORK/build" -j2 >/dev/null
"$WORK/build/consumer"
# The estimator libraries without apps: no OpenCV looked for (project_estimator/CMakeLists.txt).
cmake -S "$SRC/../project_estimator" -B "$WORK/build_estimator" -DCMAKE_PREFIX_PATH="$WORK/prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$WORK/build_estimator" -j2 >/dev/null
"$WORK/build_estimator/consumer_estimator"
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
