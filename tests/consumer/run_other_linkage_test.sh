#!/usr/bin/env bash
# The other linkage: the main build's libraries are static (BUILD_SHARED_LIBS=OFF, the default)
# or shared; this builds the libraries and apps with the other one in <build>-other (a sibling
# of the build folder: at the same depth, every compile command equals the main build's and
# ccache serves it, doc/building.md), installs them into a prefix, checks the installed library
# files, builds the consumer projects against them, runs them and an installed app (which must
# load the installed libraries without LD_LIBRARY_PATH), then removes <build>-other.
# Usage: run_other_linkage_test.sh ROOT BUILD SHARED(ON|OFF: the main build's) [cmake args...]
set -euo pipefail
ROOT="$1"; BUILD="${2%/}"; MAIN_SHARED="$3"; shift 3
case "$MAIN_SHARED" in ON|on|1|TRUE|true) OTHER=OFF ;; *) OTHER=ON ;; esac
OUT="$BUILD-other"
WORK="$OUT/work"
rm -rf "$OUT"
export CCACHE_BASEDIR="$ROOT"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
step() {  # runs a command quietly; on failure prints its output and fails
  if ! "$@" >"$log" 2>&1; then
    tail -n 60 "$log"; echo "other linkage: failed: $*" >&2; exit 1
  fi
}
step cmake -S "$ROOT" -B "$OUT" -DBUILD_SHARED_LIBS="$OTHER" -DDYNSLAM_BUILD_TESTS=OFF \
  -DDYNSLAM_BUILD_BENCH=OFF -DDYNSLAM_FUZZ=OFF "$@"
step cmake --build "$OUT" -j2
step cmake --install "$OUT" --prefix "$WORK/prefix"
LIB="$(find "$WORK/prefix" -maxdepth 2 -type d -name 'lib*' | head -n 1)"
shared_libs="$(find "$LIB" -maxdepth 1 -name 'libdynslam_*.so' ! -name 'libdynslam_slam_services.so' | wc -l)"
static_libs="$(find "$LIB" -maxdepth 1 -name 'libdynslam_*.a' | wc -l)"
if [ "$OTHER" = ON ]; then
  [ "$shared_libs" -eq 11 ] && [ "$static_libs" -eq 0 ] ||
    { echo "other linkage: expected 11 shared libraries and no archive in $LIB, found $shared_libs and $static_libs" >&2; exit 1; }
else
  [ "$static_libs" -eq 11 ] && [ "$shared_libs" -eq 0 ] ||
    { echo "other linkage: expected 11 archives and no shared library in $LIB, found $static_libs and $shared_libs" >&2; exit 1; }
fi
source "$ROOT/tests/consumer/consumer_projects.sh"
build_consumers "$WORK/prefix" "$WORK" step
# Which dynslam libraries each binary loads, and from where: with shared libraries, only those
# of the install tree (RUNPATH; the build folder is removed first so it cannot serve them).
rm -rf "$OUT/libs" "$OUT/apps"
unset LD_LIBRARY_PATH
for bin in "$WORK/build/consumer" "$WORK/build_estimator/consumer_estimator" \
           "$WORK/prefix/bin/dynslam-run"; do
  loaded="$(ldd "$bin" | grep -o 'libdynslam_[a-z_]*\.so[^ ]* => [^ ]*' || true)"
  if [ "$OTHER" = ON ]; then
    [ -n "$loaded" ] || { echo "other linkage: $bin loads no libdynslam_*.so" >&2; exit 1; }
    while read -r lib _ path; do
      [ "$path" != not ] || { echo "other linkage: $bin cannot find $lib (RUNPATH)" >&2; exit 1; }
      [ "$(dirname "$(realpath "$path")")" = "$(realpath "$LIB")" ] || {
        echo "other linkage: $bin loads $path, not from $LIB:" >&2; echo "$loaded" >&2; exit 1; }
    done <<< "$loaded"
  else
    [ -z "$loaded" ] || { echo "other linkage: $bin loads $loaded in a static build" >&2; exit 1; }
  fi
done
# The installed app runs: the installed highway INI and rawlog through dynslam-run, no figures.
step "$WORK/prefix/bin/dynslam-run" -c "$WORK/prefix/share/dynslam/config/run_highway.ini" \
  --no-figures -q -o "$WORK/run"
test -s "$WORK/run/ego.csv"
echo "other linkage (BUILD_SHARED_LIBS=$OTHER): 11 libraries installed, consumers and dynslam-run ok"
rm -rf "$OUT"
