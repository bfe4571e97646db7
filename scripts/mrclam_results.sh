#!/usr/bin/env bash
# The real-data results of doc/results/real-data.md, section 5: imports one MRCLAM dataset for each of
# the five robots as ego and runs the filters of dynslam-compare on each.
#
#   scripts/mrclam_results.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
#   DATASET_DIR  an MRCLAM folder (e.g. MRCLAM_Dataset6 from the UTIAS site; not shipped)
#   OUT_DIR      default out/mrclam_results
#   BUILD_DIR    a configured build with the targets dynslam-mrclam, dynslam-compare and
#                dynslam-realdata-report (default build)
#
# Per robot N it writes OUT_DIR/robotN/ (the import), OUT_DIR/robotN/compare/ (dynslam-compare:
# metrics.csv, estimates, figures) and OUT_DIR/robotN/report/ (dynslam-realdata-report: the
# extra columns: tracked robots, gated-out counts, the dynamic filter with the gate off, and
# tracked.png), then OUT_DIR/summary.csv, OUT_DIR/tracked_robots.csv and OUT_DIR/table.md.
# Development only: no test needs this script or the full datasets.
set -euo pipefail

if [[ $# -lt 1 ]]; then
	sed -n '2,16p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/mrclam_results}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
[[ -d "$DATA" ]] || { echo "mrclam_results.sh: no dataset folder '$DATA'" >&2; exit 1; }

find_exe() {
	local p
	p=$(find "$BUILD" -type f -perm -u+x -name "$1" 2>/dev/null | head -n 1)
	[[ -n "$p" ]] || { echo "mrclam_results.sh: $1 not found under $BUILD (build it first)" >&2; exit 1; }
	echo "$p"
}
IMPORT=$(find_exe dynslam-mrclam)
COMPARE=$(find_exe dynslam-compare)
REPORT=$(find_exe dynslam-realdata-report)

mkdir -p "$OUT"
: > "$OUT/summary.csv"
: > "$OUT/tracked_robots.csv"
for N in 1 2 3 4 5; do
	D="$OUT/robot$N"
	echo "== robot $N"
	"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D" --config "$SRC/config/mrclam.ini" > "$D.import.log"
	"$COMPARE" -q -c "$SRC/config/mrclam_compare.ini" -r "$D/robot$N.rawlog" --out "$D/compare" \
		> "$D.compare.log"
	"$REPORT" -c "$SRC/config/mrclam_compare.ini" -r "$D/robot$N.rawlog" --out "$D/report" \
		--label "robot$N"
	if [[ ! -s "$OUT/summary.csv" ]]; then
		head -n 1 "$D/report/summary.csv" > "$OUT/summary.csv"
		head -n 1 "$D/report/tracked_robots.csv" > "$OUT/tracked_robots.csv"
	fi
	tail -n +2 "$D/report/summary.csv" >> "$OUT/summary.csv"
	tail -n +2 "$D/report/tracked_robots.csv" >> "$OUT/tracked_robots.csv"
done

# One markdown table (the one in doc/results/real-data.md, section 5.3).
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
function f(x, d) { return (x == "nan" || x == "-nan" || x == "") ? "-" : sprintf("%." d "f", x) }
{
	if (!hdr++) {
		print "| ego | filter | ATE [m] | landmarks [m] | tracked robots [m] (n) | ego ANEES [95% bounds] | ANIS [95% bounds] | gated out / used | ms/step |"
		print "|---|---|---|---|---|---|---|---|---|"
	}
	tr = ($c["filter"] ~ /^dynamic/) ? f($c["tracked_rmse"], 3) " (" $c["tracked_n"] ")" : "-"
	gate = ($c["filter"] ~ /^dynamic/) ? $c["gated_out"] " / " $c["static_updates"] : "-"
	printf "| %s | %s | %s | %s | %s | %s [%s, %s] | %s [%s, %s] | %s | %s |\n", $c["label"], $c["filter"],
		f($c["ate"], 3), f($c["landmark_rmse"], 3), tr, f($c["ego_anees"], 2), f($c["ego_anees_lo"], 2),
		f($c["ego_anees_hi"], 2), f($c["nis_anis"], 2), f($c["nis_anis_lo"], 2), f($c["nis_anis_hi"], 2),
		gate, f($c["ms_per_step"], 2)
}' "$OUT/summary.csv" > "$OUT/table.md"
cat "$OUT/table.md"
echo "wrote $OUT/summary.csv, $OUT/tracked_robots.csv, $OUT/table.md and per-robot folders"
