#!/usr/bin/env bash
# The detector-box results of doc/boxes.md (issue 31): imports KITTI tracking sequences with a
# 3-D detector's boxes (no track IDs) and runs dynslam-compare's rows static_all, odometry,
# tracker_baseline and default on each; collects every row's ego and tracking metrics.
#
#   scripts/kitti_detections.sh DATA_DIR DET_DIR [OUT_DIR] [BUILD_DIR] [SEQUENCES]
#
#   DATA_DIR   label_02/SSSS.txt and poses/SSSS.txt (the ground truth; not shipped)
#   DET_DIR    the detector's folder: CLASS/SSSS.txt (PointRCNN, AB3DMOT's format) and
#              calib/SSSS.txt (or KITTI_CALIB=DIR); never copied into the project
#   OUT_DIR    default out/kitti_detections
#   BUILD_DIR  a build with dynslam-kitti and dynslam-compare (default build)
#   SEQUENCES  default "0000 ... 0010"
# KITTI_INI=FILE replaces config/compare_kitti_detections.ini, KITTI_IMPORT_INI=FILE
# config/kitti_detections.ini; KITTI_FILTERS=a,b,... is dynslam-compare's --filters;
# KITTI_VIDEO=1 also writes OUT_DIR/S/compare/video.mp4.
# Writes OUT_DIR/S/ (import), OUT_DIR/S/compare/, OUT_DIR/import_times.csv, OUT_DIR/summary.csv
# (one row per sequence and filter, the columns the table uses) and OUT_DIR/table.md. Development only: no test needs it.
set -euo pipefail
if [[ $# -lt 2 ]]; then
	sed -n '2,18p' "$0"
	exit 1
fi
DATA=$1
DET=$2
OUT=${3:-out/kitti_detections}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${4:-$SRC/build}
SEQS=${5:-"0000 0001 0002 0003 0004 0005 0006 0007 0008 0009 0010"}
CALIB=${KITTI_CALIB:-$DET/../calib}
[[ -d "$CALIB" ]] || CALIB=$DET/calib
find_exe() {
	local p=$BUILD/apps/$1/$1
	[[ -x "$p" ]] && { echo "$p"; return; }
	p=$(find "$BUILD" -type f -perm -u+x -name "$1" 2>/dev/null | head -n 1)
	[[ -n "$p" ]] || { echo "kitti_detections.sh: $1 not found under $BUILD" >&2; exit 1; }
	echo "$p"
}
IMPORT=$(find_exe dynslam-kitti)
COMPARE=$(find_exe dynslam-compare)
INI=${KITTI_INI:-$SRC/config/compare_kitti_detections.ini}
IMPORT_INI=${KITTI_IMPORT_INI:-$SRC/config/kitti_detections.ini}
mkdir -p "$OUT"
: > "$OUT/import_times.csv"
for S in $SEQS; do
	D="$OUT/$S"
	echo "== sequence $S"
	start=$(date +%s.%N)
	"$IMPORT" --labels "$DATA/label_02" --poses "$DATA/poses" --sequence "$S" --out "$D" \
		-c "$IMPORT_INI" --detections "$DET" --calib "$CALIB" > "$OUT/$S.import.log"
	end=$(date +%s.%N)
	echo "import_seconds,$S,$(echo "$end - $start" | bc)" >> "$OUT/import_times.csv"
	VIDEO=()
	if [[ -n "${KITTI_FILTERS:-}" ]]; then VIDEO+=(--filters "$KITTI_FILTERS"); fi
	if [[ -n "${KITTI_VIDEO:-}" ]]; then VIDEO+=(--video "$D/compare/video.mp4"); fi
	"$COMPARE" -c "$INI" -r "$D/kitti_$S.rawlog" --out "$D/compare" -q "${VIDEO[@]}" \
		> "$OUT/$S.compare.log" 2>&1 || { echo "compare failed on $S (see $OUT/$S.compare.log)"; continue; }
done
python3 "$SRC/scripts/kitti_detections_table.py" "$OUT" $SEQS > "$OUT/table.md"
cat "$OUT/table.md"
