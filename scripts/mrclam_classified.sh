#!/usr/bin/env bash
# Issue 12 on real data (doc/results/real-data.md section 6, doc/results/classification.md): for each of the five
# robots of an MRCLAM dataset, imports it labelled and with anonymous IDs (dynslam-mrclam
# --anonymous --seed 1), runs dynslam-compare with config/mrclam_compare.ini on the labelled
# rawlog (static_all, static_landmarks_only, dynamic, dynamic_classified) and on the anonymous
# one (static_all, dynamic_classified), and prints one table row per robot.
#
#   scripts/mrclam_classified.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
# INI=file overrides config/mrclam_compare.ini. Development only: no test needs this script or
# the full datasets.
set -euo pipefail
if [[ $# -lt 1 ]]; then
	sed -n '2,10p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/mrclam_classified}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
[[ -d "$DATA" ]] || { echo "mrclam_classified.sh: no dataset folder '$DATA'" >&2; exit 1; }
IMPORT=$BUILD/apps/dynslam-mrclam/dynslam-mrclam
COMPARE=$BUILD/apps/dynslam-compare/dynslam-compare
for exe in "$IMPORT" "$COMPARE"; do
	[[ -x "$exe" ]] || { echo "mrclam_classified.sh: $exe not built" >&2; exit 1; }
done
INI=${INI:-$SRC/config/mrclam_compare.ini}
mkdir -p "$OUT"
echo "| ego | static_all ATE [m] | dynamic ATE [m] | dynamic_classified ATE [m], labelled / anonymous rawlog | class P / R / F1 (anonymous) | group ARI |"
echo "|---|---|---|---|---|---|"
for N in 1 2 3 4 5; do
	D="$OUT/robot$N"
	"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D" --config "$SRC/config/mrclam.ini" > "$D.import.log"
	"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D" --base "robot${N}_anon" --anonymous --seed 1 \
		--config "$SRC/config/mrclam.ini" > "$D.import_anon.log"
	"$COMPARE" -q -c "$INI" -r "$D/robot$N.rawlog" --out "$D/compare" --no-figures > "$D.compare.log"
	"$COMPARE" -q -c "$INI" -r "$D/robot${N}_anon.rawlog" --filters static_all,dynamic_classified \
		--out "$D/compare_anon" --no-figures > "$D.compare_anon.log"
	python3 - "$D/compare/metrics.csv" "$D/compare_anon/metrics.csv" "$N" <<'PY'
import csv, sys
lab = {r['filter']: r for r in csv.DictReader(open(sys.argv[1]))}
an = {r['filter']: r for r in csv.DictReader(open(sys.argv[2]))}
f = lambda r, k: '%.3f' % float(r[k]) if r.get(k) not in (None, '') else '-'
c = an['dynamic_classified']
print('| robot %s | %s | %s | %s / %s | %s / %s / %s | %s |' % (sys.argv[3], f(lab['static_all'], 'ate'),
      f(lab['dynamic'], 'ate'), f(lab['dynamic_classified'], 'ate'), f(c, 'ate'),
      f(c, 'class_precision'), f(c, 'class_recall'), f(c, 'class_f1'), f(c, 'group_ari')))
if abs(float(lab['static_all']['ate']) - float(an['static_all']['ate'])) > 1e-9:
    print('  (static_all differs between the labelled and anonymous rawlogs: %s vs %s)' % (lab['static_all']['ate'], an['static_all']['ate']))
PY
done
