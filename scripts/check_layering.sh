#!/usr/bin/env bash
# Checks the library layering of doc/building.md on CMake's own target graph and on the
# compiler's view of the public headers; exits 1 with the violations, 0 if there is none:
#  1. dynslam::core and dynslam::estimator link no MRPT (pure Eigen);
#  2. estimator, common, framework, sim, eval, mrclam and kitti do not depend on dynslam::ekf
#     or dynslam::apps;
#  3. no public header of common, framework or sim includes, even indirectly,
#     CKalmanFilterCapable.h or CDynamicKFSLAM2D.h.
# Usage: scripts/check_layering.sh [work dir] (default: a temporary directory; a fresh CMake
# configure of the libraries only, ~10-30 s; nothing is compiled).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
WORK="${1:-}"
if [[ -z "$WORK" ]]; then
	WORK="$(mktemp -d)"
	trap 'rm -rf "$WORK"' EXIT
fi
CXX_BIN="${CXX:-c++}"
cmake -S "$ROOT" -B "$WORK" -G "Unix Makefiles" -DDYNSLAM_BUILD_TESTS=OFF -DDYNSLAM_BUILD_APPS=OFF \
	-DDYNSLAM_BUILD_BENCH=OFF --graphviz="$WORK/graph/dynslam.dot" >/dev/null
G="$WORK/graph/dynslam.dot"
fail=0
violation() {
	echo "check_layering: $*"
	fail=1
}
# Names of the targets in the dependency graph of one target (labels of the .dot file).
deps() { grep -o 'label = "[^"\\]*' "$G.$1" | sed 's/label = "//' | sort -u; }

for lib in core estimator common ekf framework sim eval mrclam kitti apps; do
	[[ -f "$G.dynslam_$lib" ]] || violation "no target dynslam_$lib in the graph ($G.dynslam_$lib)"
done
for lib in core estimator; do
	if deps "dynslam_$lib" | grep -q '^mrpt::'; then
		violation "dynslam::$lib depends on MRPT: $(deps "dynslam_$lib" | grep '^mrpt::' | tr '\n' ' ')"
	fi
done
for lib in estimator common framework sim eval mrclam kitti; do
	for upper in dynslam_ekf dynslam_apps; do
		if deps "dynslam_$lib" | grep -qx "$upper"; then
			violation "dynslam_$lib depends on $upper"
		fi
	done
done
for lib in common framework sim; do
	flags="$WORK/libs/$lib/CMakeFiles/dynslam_$lib.dir/flags.make"
	inc=$(grep '^CXX_INCLUDES' "$flags" | cut -d= -f2-)
	tu="$WORK/layering_$lib.cpp"
	: >"$tu"
	while IFS= read -r -d '' h; do echo "#include \"$h\"" >>"$tu"; done \
		< <(find "$ROOT/libs/$lib/include" -name '*.h' -print0 | sort -z)
	# shellcheck disable=SC2086
	if ! "$CXX_BIN" -std=c++17 $inc -M "$tu" >"$tu.d" 2>"$tu.err"; then
		violation "the public headers of libs/$lib do not preprocess with its own include" \
			"paths: $(grep -m1 'error' "$tu.err")"
		continue
	fi
	bad=$(tr ' \\' '\n\n' <"$tu.d" | grep -E 'CKalmanFilterCapable\.h|CDynamicKFSLAM2D\.h' || true)
	if [[ -n "$bad" ]]; then
		violation "a public header of libs/$lib includes $(echo "$bad" | tr '\n' ' ')"
	fi
done
if [[ $fail -eq 0 ]]; then
	echo "check_layering: ok (core and estimator without MRPT; estimator, common, framework," \
		"sim, eval, mrclam, kitti without the EKF and the apps; headers of common, framework, sim" \
		"without the Kalman filter)"
fi
exit $fail
