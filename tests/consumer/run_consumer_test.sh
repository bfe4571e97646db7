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
