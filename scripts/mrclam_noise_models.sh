#!/usr/bin/env bash
# The motion-noise-model comparison of doc/results/real-data.md 5.11 (issue 17 item 2): imports one
# MRCLAM dataset for each robot as ego once per odometry noise model ([MRCLAM_Import] keys on
# top of config/mrclam.ini) and runs the dynamic EKF of config/mrclam_compare.ini once per
# outlier method, every other setting unchanged.
#
#   scripts/mrclam_noise_models.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
# Writes OUT_DIR/<model>/robotN/<method>/metrics.csv and OUT_DIR/models.csv
# (robot,model,method,ate,ate_aligned,ego_anees). Development only: no test needs it.
# MODELS (default "white inflated"): white = config/mrclam.ini's fit with odo_noise_model =
# white; inflated = the same with odo_noise_model = inflated and the taus of config/mrclam.ini;
# tA_B (e.g. t15_1) = inflated with tau_xy = A, tau_phi = B; xN (e.g. x4) = the white fit with
# every variance times N (for the reader: a uniform scale).
# METHODS (default "gate huber"): outlier_method values.
set -euo pipefail
if [[ $# -lt 1 ]]; then
	sed -n '2,15p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/mrclam_noise_models}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
# find_exe, with_keys
source "$SRC/scripts/mrclam_variants.sh"
IMPORT=$(find_exe dynslam-mrclam)
COMPARE=$(find_exe dynslam-compare)
# [MRCLAM_Import] keys of a model (appended after config/mrclam.ini's, so they win)
import_keys() {
	case $1 in
	white) echo "odo_noise_model = white" ;;
	inflated) echo "odo_noise_model = inflated" ;;
	t*_*)
		local a=${1#t}
		printf 'odo_noise_model = inflated\nodo_tau_xy = %s\nodo_tau_phi = %s\n' "${a%_*}" "${a#*_}" ;;
	x*)
		local k=${1#x}
		awk -F' *= *' -v k="$k" '/^\[MRCLAM_Import\]/ { s = 1; next } /^\[/ { s = 0 }
			s && $1 ~ /^odo_var_/ { print $1 " = " $2 * k }
			s && $1 ~ /^odo_std_.*_min$/ { print $1 " = " $2 * sqrt(k) }' "$SRC/config/mrclam.ini"
		echo "odo_noise_model = white" ;;
	*) echo "unknown model $1" >&2; exit 1 ;;
	esac
}
CSV="$OUT/models.csv"
mkdir -p "$OUT"
echo "robot,model,method,ate,ate_aligned,ego_anees" > "$CSV"
for MODEL in ${MODELS:-white inflated}; do
	mkdir -p "$OUT/$MODEL"
	keys=$(import_keys "$MODEL")
	# the model's keys replace config/mrclam.ini's own lines for them, at the top of the section
	awk -v k="$keys" 'BEGIN { n = split(k, L, "\n"); for (i = 1; i <= n; ++i) { split(L[i], kv, / *= */); K[kv[1]] = 1 } }
		/^\[/ { s = ($0 == "[MRCLAM_Import]") }
		s && !/^\[/ { split($0, kv, / *= */); if (kv[1] in K) next }
		{ print } /^\[MRCLAM_Import\]$/ { print k }' "$SRC/config/mrclam.ini" > "$OUT/$MODEL/mrclam.ini"
	for N in ${ROBOTS:-1 2 3 4 5}; do
		D="$OUT/$MODEL/robot$N"
		mkdir -p "$D"
		"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D" --config "$OUT/$MODEL/mrclam.ini" \
			> "$D/import.log"
		for M in ${METHODS:-gate huber}; do
			with_keys "outlier_method = $M" < "$SRC/config/mrclam_compare.ini" > "$D/$M.ini"
			"$COMPARE" -q -c "$D/$M.ini" -r "$D/robot$N.rawlog" --out "$D/$M" --filters dynamic \
				--no-figures > "$D/$M.log" 2>&1 || { echo "robot $N $MODEL $M: failed (see $D/$M.log)"; continue; }
			awk -F, -v r="$N" -v mo="$MODEL" -v m="$M" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
				{ print r "," mo "," m "," $c["ate"] "," $c["ate_aligned"] "," $c["ego_anees"] }' \
				"$D/$M/metrics.csv" >> "$CSV"
		done
	done
done
column -s, -t "$CSV"
