#!/usr/bin/env bash
# The outlier-method comparison of doc/real-data.md 5.9 (issue 17): imports one MRCLAM dataset
# for each robot as ego and runs the dynamic EKF of config/mrclam_compare.ini once per
# outlier_method, every other setting unchanged (the method's parameters are the defaults).
#
#   scripts/mrclam_outliers.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
# Writes OUT_DIR/robotN/<method>/metrics.csv and OUT_DIR/outliers.csv
# (robot,method,ate,ate_aligned,ego_anees). Development only: no test needs it.
set -euo pipefail
if [[ $# -lt 1 ]]; then
	sed -n '2,9p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/mrclam_outliers}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
find_exe() {
	local p
	p=$(find "$BUILD" -type f -perm -u+x -name "$1" 2>/dev/null | head -n 1)
	[[ -n "$p" ]] || { echo "mrclam_outliers.sh: $1 not found under $BUILD" >&2; exit 1; }
	echo "$p"
}
IMPORT=$(find_exe dynslam-mrclam)
COMPARE=$(find_exe dynslam-compare)
METHODS=${METHODS:-"gate none huber cauchy gate_recovery jcbb"}
mkdir -p "$OUT"
echo "robot,method,ate,ate_aligned,ego_anees" > "$OUT/outliers.csv"
for N in ${ROBOTS:-1 2 3 4 5}; do
	D="$OUT/robot$N"
	mkdir -p "$D"
	[[ -s "$D/robot$N.rawlog" ]] ||
		"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D" --config "$SRC/config/mrclam.ini" \
			> "$D/import.log"
	for M in $METHODS; do
		# the [DynamicKFSLAM] section gets the one key; everything else as shipped
		awk -v m="$M" '{ print } /^\[DynamicKFSLAM\]$/ { print "outlier_method = " m }' \
			"$SRC/config/mrclam_compare.ini" > "$D/$M.ini"
		"$COMPARE" -q -c "$D/$M.ini" -r "$D/robot$N.rawlog" --out "$D/$M" --filters dynamic \
			--no-figures > "$D/$M.log" 2>&1 || { echo "robot $N $M: failed (see $D/$M.log)"; continue; }
		awk -F, -v r="$N" -v m="$M" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
			{ print r "," m "," $c["ate"] "," $c["ate_aligned"] "," $c["ego_anees"] }' \
			"$D/$M/metrics.csv" >> "$OUT/outliers.csv"
	done
done
column -s, -t "$OUT/outliers.csv"
