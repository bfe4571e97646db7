# Sourced by the consumer tests: builds and runs the two external projects (project: every
# component; project_estimator: all but apps, no OpenCV) against an install prefix.
# build_consumers PREFIX WORK [RUN]: RUN (default: plain) runs each command, e.g. a quiet wrapper.
build_consumers() {
  local prefix="$1" work="$2" run="${3:-}" src
  src="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
  $run cmake -S "$src/project" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release
  $run cmake --build "$work/build" -j2
  $run "$work/build/consumer"
  $run cmake -S "$src/project_estimator" -B "$work/build_estimator" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_BUILD_TYPE=Release
  $run cmake --build "$work/build_estimator" -j2
  $run "$work/build_estimator/consumer_estimator"
}
