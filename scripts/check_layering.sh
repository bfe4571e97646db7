#!/usr/bin/env bash
# Checks the library layering of doc/building.md on CMake's own target graph and on the
# compiler's view of the public headers; exits 1 with the violations, 0 if there is none:
#  1. every arrow (direct link dependency, public or private) of every dynslam library is in
#     the table ALLOWED below, and every dynslam library of the graph has a row in it;
#  2. core, io and estimator reach no MRPT, even indirectly (pure Eigen); the EKF's link
#     interface reaches neither OpenCV nor mrpt::img through a dynslam library (dynslam::eval
#     is not below it);
#  3. estimator, common, framework, sim, eval, mrclam and kitti do not depend, even indirectly,
#     on dynslam::ekf or dynslam::apps;
#  4. no public header of common, framework or sim includes, even indirectly,
#     CKalmanFilterCapable.h or CDynamicKFSLAM2D.h, and no public header of core, io or
#     estimator includes an MRPT or OpenCV header (the compiler's -M with the library's own
#     include paths; a header that needs another library's include path fails too).
#  5. every public header of a library is under its dynslam/<lib>/ folder.
# Usage: scripts/check_layering.sh [work dir] (default: a temporary directory; a fresh CMake
# configure of the libraries only, ~10-30 s; nothing is compiled).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"

# The table of allowed arrows: library -> the dynslam libraries and third-party targets it may
# link directly (doc/building.md, "Libraries and what links what"). dynslam_mrpt_pch is the
# shared precompiled MRPT header (an internal object library, reused, not linked). A pattern
# may end in '*'. A new arrow or a new library is a decision: add it here and to the doc.
MRPT_BASE="mrpt::obs mrpt::poses mrpt::config"
declare -A ALLOWED=(
	[core]="Eigen3::Eigen"
	[io]="dynslam::core Eigen3::Eigen"
	[estimator]="dynslam::core"
	[common]="dynslam::core dynslam::estimator Eigen3::Eigen $MRPT_BASE mrpt::io mrpt::serialization
	          mrpt::tclap dynslam_mrpt_pch"
	[ekf]="dynslam::core dynslam::estimator dynslam::common $MRPT_BASE mrpt::bayes mrpt::slam
	       mrpt::system dynslam_mrpt_pch"
	[framework]="dynslam::core dynslam::estimator dynslam::common Eigen3::Eigen $MRPT_BASE
	             dynslam_mrpt_pch"
	[sim]="dynslam::core dynslam::io dynslam::common $MRPT_BASE mrpt::random mrpt::io
	       mrpt::serialization mrpt::img mrpt::system mrpt::tclap dynslam_mrpt_pch"
	[eval]="dynslam::core dynslam::io Eigen3::Eigen mrpt::img"
	[mrclam]="dynslam::core dynslam::io dynslam::common $MRPT_BASE mrpt::io mrpt::serialization
	          mrpt::system mrpt::tclap dynslam_mrpt_pch"
	[kitti]="dynslam::core dynslam::io dynslam::common $MRPT_BASE mrpt::io mrpt::serialization
	         mrpt::system mrpt::tclap dynslam_mrpt_pch"
	[apps]="dynslam::core dynslam::io dynslam::common dynslam::ekf dynslam::framework dynslam::sim
	        dynslam::eval $MRPT_BASE mrpt::slam mrpt::io mrpt::serialization mrpt::system
	        mrpt::opengl mrpt::tclap opencv_* dynslam_mrpt_pch"
)
LIBS="core io estimator common ekf framework sim eval mrclam kitti apps"

WORK="${1:-}"
if [[ -z "$WORK" ]]; then
	WORK="$(mktemp -d)"
	trap 'rm -rf "$WORK"' EXIT
fi
CXX_BIN="${CXX:-c++}"
rm -rf "$WORK/graph"
cmake -S "$ROOT" -B "$WORK" -G "Unix Makefiles" -DDYNSLAM_BUILD_TESTS=OFF -DDYNSLAM_BUILD_APPS=OFF \
	-DDYNSLAM_BUILD_BENCH=OFF --graphviz="$WORK/graph/dynslam.dot" >/dev/null
G="$WORK/graph/dynslam.dot"
fail=0
violation() {
	echo "check_layering: $*"
	fail=1
}
# The direct arrows of the whole graph, one "from to" per line (dynslam_x written dynslam::x,
# except the internal dynslam_mrpt_pch).
arrows() {
	grep -o '// [^ ]* -> [^ ]*$' "$G" | sed 's#^// ##; s# -> # #' |
		awk '{ for (i = 1; i <= 2; ++i) if ($i ~ /^dynslam_/ && $i != "dynslam_mrpt_pch")
			sub(/^dynslam_/, "dynslam::", $i); print }' | sort -u
}
ARROWS="$(arrows)"
direct() { awk -v f="dynslam::$1" '$1 == f { print $2 }' <<<"$ARROWS"; }
allowed() { # allowed LIB TARGET
	local p
	for p in ${ALLOWED[$1]}; do
		# shellcheck disable=SC2053
		[[ "$2" == $p ]] && return 0
	done
	return 1
}
# The dynslam libraries reachable from one (itself included), by the direct arrows.
closure() {
	local todo=("$1") seen=" $1 " l d
	while ((${#todo[@]})); do
		l="${todo[0]}"
		todo=("${todo[@]:1}")
		for d in $(direct "$l" | sed -n 's#^dynslam::##p'); do
			[[ "$seen" == *" $d "* ]] || {
				seen="$seen$d "
				todo+=("$d")
			}
		done
	done
	echo "$seen"
}

# 1. The table.
for lib in $LIBS; do
	grep -q "\"dynslam_$lib\\\\n" "$G" || violation "no target dynslam_$lib in the graph"
	for d in $(direct "$lib"); do
		allowed "$lib" "$d" || violation "arrow dynslam::$lib -> $d is not in the table" \
			"(scripts/check_layering.sh ALLOWED, doc/building.md)"
	done
done
for t in $(awk '{ print $1 }' <<<"$ARROWS" | grep '^dynslam::' | sort -u); do
	[[ " $LIBS " == *" ${t#dynslam::} "* ]] || violation "library $t has no row in the table"
done
for t in $(grep -o 'label = "dynslam_[a-z_]*' "$G" | sed 's#label = "##' | sort -u); do
	case "$t" in
	dynslam_mrpt_pch) ;;
	*) [[ " $LIBS " == *" ${t#dynslam_} "* ]] || violation "target $t has no row in the table" ;;
	esac
done
# 2. Pure libraries, and the EKF without the evaluation's image dependencies.
for lib in core io estimator; do
	for l in $(closure "$lib"); do
		bad=$(direct "$l" | grep -E '^mrpt::|^opencv' | tr '\n' ' ' || true)
		[[ -z "$bad" ]] || violation "dynslam::$lib reaches MRPT/OpenCV through dynslam::$l: $bad"
	done
done
for l in $(closure ekf); do
	bad=$(direct "$l" | grep -E '^mrpt::img$|^opencv' | tr '\n' ' ' || true)
	[[ -z "$bad" ]] || violation "dynslam::ekf's link interface reaches $bad through dynslam::$l"
done
# 3. Nothing below the EKF and the apps depends on them.
for lib in estimator common framework sim eval mrclam kitti; do
	for upper in ekf apps; do
		[[ " $(closure "$lib") " != *" $upper "* ]] || violation "dynslam::$lib depends on dynslam::$upper"
	done
done
# 4. Public headers, as the compiler sees them.
headers_deps() { # LIB: $WORK/layering_LIB.deps: the files its public headers include, one a line
	local lib="$1" flags inc tu
	flags="$WORK/libs/$lib/CMakeFiles/dynslam_$lib.dir/flags.make"
	inc=$(grep '^CXX_INCLUDES' "$flags" | cut -d= -f2- || true)
	tu="$WORK/layering_$lib.cpp"
	: >"$tu"
	while IFS= read -r -d '' h; do echo "#include \"$h\"" >>"$tu"; done \
		< <(find "$ROOT/libs/$lib/include" -name '*.h' -print0 | sort -z)
	# shellcheck disable=SC2086
	if ! "$CXX_BIN" -std=c++17 $inc -M "$tu" >"$tu.d" 2>"$tu.err"; then
		violation "the public headers of libs/$lib do not preprocess with its own include" \
			"paths: $(grep -m1 'error' "$tu.err")"
		return 1
	fi
	tr ' \\' '\n\n' <"$tu.d" | grep -v '^$' >"$WORK/layering_$lib.deps"
}
for lib in common framework sim; do
	headers_deps "$lib" || continue
	bad=$(grep -E 'CKalmanFilterCapable\.h|CDynamicKFSLAM2D\.h' "$WORK/layering_$lib.deps" || true)
	[[ -z "$bad" ]] || violation "a public header of libs/$lib includes $(echo "$bad" | tr '\n' ' ')"
done
for lib in core io estimator; do
	headers_deps "$lib" || continue
	bad=$(grep -E '/mrpt/|/opencv' "$WORK/layering_$lib.deps" | head -3 || true)
	[[ -z "$bad" ]] || violation "a public header of libs/$lib includes $(echo "$bad" | tr '\n' ' ')"
done
# 5. Every public header is under dynslam/<lib>/ (MRPT's mrpt/<lib>/ pattern): two libraries
#    never offer the same include path, and an include names the library it needs.
for lib in $LIBS; do
	[[ -d "$ROOT/libs/$lib/include" ]] || continue
	bad=$(cd "$ROOT/libs/$lib/include" && find . -name '*.h' ! -path "./dynslam/$lib/*" | head -3)
	[[ -z "$bad" ]] || violation "libs/$lib has public headers outside dynslam/$lib/: $(echo "$bad" | tr '\n' ' ')"
done
if [[ $fail -eq 0 ]]; then
	echo "check_layering: ok (every arrow of $(wc -w <<<"$LIBS") libraries in the table; core, io," \
		"estimator without MRPT; the EKF without OpenCV and mrpt::img; nothing below the EKF" \
		"and the apps depends on them; headers of common, framework, sim without the Kalman" \
		"filter, of core, io, estimator without MRPT; every public header under dynslam/<lib>/)"
fi
exit $fail
