#!/usr/bin/env bash
# The KITTI results of doc/kitti.md: imports KITTI tracking sequences 0000-0010 as bird's-eye
# rawlogs and runs the filters of dynslam-compare on each, with the extra metrics of
# dynslam-kitti-report (RPE, object position and motion errors, the annotation jitter floor).
#
#   scripts/kitti_results.sh DATA_DIR [OUT_DIR] [BUILD_DIR] [SEQUENCES]
#
#   DATA_DIR   a folder with label_02/SSSS.txt and poses/SSSS.txt (KITTI tracking labels and a
#              metric camera trajectory per sequence; not shipped, see doc/kitti.md)
#   OUT_DIR    default out/kitti_results
#   BUILD_DIR  a configured build with the targets dynslam-kitti, dynslam-compare and
#              dynslam-kitti-report (test area kitti) (default build)
#   SEQUENCES  default "0000 0001 0002 0003 0004 0005 0006 0007 0008 0009 0010"
#
# Per sequence S it writes OUT_DIR/S/ (the import), OUT_DIR/S/compare/ (dynslam-compare:
# metrics.csv, estimates, figures) and OUT_DIR/S/report/ (summary.csv, objects.csv, map.png),
# then OUT_DIR/summary.csv and OUT_DIR/table.md. Development only: no test needs this script.
# KITTI_NO_COMPARE=1 skips dynslam-compare (the report runs the same three filters; this halves
# the run time on a loaded machine). KITTI_INI=FILE replaces config/compare_kitti.ini (both
# tools); KITTI_IMPORT_INI=FILE replaces config/kitti.ini (the import, e.g. with
# pose_scale = auto); KITTI_FILTERS=a,b,... is the report's --filters (default static_all,
# static_landmarks_only,dynamic,dynamic_nogate), e.g. for the object models of doc/kitti.md 5.6:
#   KITTI_NO_COMPARE=1 KITTI_FILTERS=static_landmarks_only,dynamic,dynamic_cv,dynamic_ctrv \
#     scripts/kitti_results.sh DIR out/kitti_motion build "0005 0006 0007 0008 0009 0010"
set -euo pipefail

if [[ $# -lt 1 ]]; then
	sed -n '2,20p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/kitti_results}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
SEQS=${4:-"0000 0001 0002 0003 0004 0005 0006 0007 0008 0009 0010"}
[[ -d "$DATA/label_02" && -d "$DATA/poses" ]] ||
	{ echo "kitti_results.sh: '$DATA' has no label_02/ and poses/ folders" >&2; exit 1; }

find_exe() {
	local p
	p=$(find "$BUILD" -type f -perm -u+x -name "$1" 2>/dev/null | head -n 1)
	[[ -n "$p" ]] || { echo "kitti_results.sh: $1 not found under $BUILD (build it first)" >&2; exit 1; }
	echo "$p"
}
IMPORT=$(find_exe dynslam-kitti)
COMPARE=$(find_exe dynslam-compare)
REPORT=$(find_exe dynslam-kitti-report)

INI=${KITTI_INI:-$SRC/config/compare_kitti.ini}
IMPORT_INI=${KITTI_IMPORT_INI:-$SRC/config/kitti.ini}
FILTERS=()
if [[ -n "${KITTI_FILTERS:-}" ]]; then FILTERS=(--filters "$KITTI_FILTERS"); fi

mkdir -p "$OUT"
: > "$OUT/summary.csv"
for S in $SEQS; do
	D="$OUT/$S"
	echo "== sequence $S"
	"$IMPORT" --labels "$DATA/label_02" --poses "$DATA/poses" --sequence "$S" --out "$D" \
		-c "$IMPORT_INI" > "$OUT/$S.import.log"
	if [[ -z "${KITTI_NO_COMPARE:-}" ]]; then
		"$COMPARE" -q -c "$INI" -r "$D/kitti_$S.rawlog" --out "$D/compare" \
			> "$OUT/$S.compare.log"
	fi
	"$REPORT" -c "$INI" -r "$D/kitti_$S.rawlog" --out "$D/report" --label "$S" \
		${FILTERS[@]+"${FILTERS[@]}"}
	if [[ ! -s "$OUT/summary.csv" ]]; then head -n 1 "$D/report/summary.csv" > "$OUT/summary.csv"; fi
	tail -n +2 "$D/report/summary.csv" >> "$OUT/summary.csv"
done

# One markdown table (doc/kitti.md, section 5).
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
function f(x, d) { return (x == "nan" || x == "-nan" || x == "") ? "-" : sprintf("%." d "f", x) }
{
	if (!hdr++) {
		print "| seq | filter | ATE [m] | RPE10 [m / deg] | map [m] | objects [m] | motion [m / deg] | floor [m / deg] | gated | ms/step |"
		print "|---|---|---|---|---|---|---|---|---|---|"
	}
	dyn = ($c["filter"] ~ /^dynamic/)
	printf "| %s | %s | %s | %s / %s | %s | %s | %s | %s / %s | %s | %s |\n", $c["label"], $c["filter"],
		($c["steps"] == "failed") ? "failed (see the log)" : f($c["ate"], 3), f($c["rpe10_t"], 3), f($c["rpe10_r_deg"], 2), f($c["map_rmse"], 3),
		dyn ? f($c["obj_pos_rmse"], 3) : "-",
		dyn ? f($c["motion_t_rmse"], 3) " / " f($c["motion_r_rmse_deg"], 2) : "-",
		f($c["floor_t_rmse"], 3), f($c["floor_r_rmse_deg"], 2),
		dyn ? $c["gated_out"] : "-", f($c["ms_per_step"], 2)
}' "$OUT/summary.csv" > "$OUT/table.md"
cat "$OUT/table.md"
echo "wrote $OUT/summary.csv, $OUT/table.md and per-sequence folders"
