#!/usr/bin/env bash
# Leave-one-robot-out check of the parameters estimated from the data (doc/results/real-data.md 5.12,
# issue 17): for each robot N of an MRCLAM dataset, every [MRCLAM_Import] parameter that
# config/mrclam.ini takes from the ground truth (std_range, std_bearing, odo_delay, odo_scale_v,
# the six odometry noise coefficients, odo_tau_xy, odo_tau_phi) is re-estimated with
# `dynslam-mrclam --estimate-noise --all-robots --leave-out N` on the other four robots
# (PASSES rounds, default 3, each starting from the previous round's values, because the delay,
# the gain and the noise fit depend on each other), then robot N is imported with them and run
# through the dynamic EKF of config/mrclam_compare.ini with each outlier method of METHODS
# (default "gate huber") and each odometry noise model of MODELS (default "white inflated").
#
#   scripts/mrclam_loro.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
# Writes OUT_DIR/robotN/loro.ini (the estimate without robot N), OUT_DIR/params.csv and
# OUT_DIR/loro.csv (robot,model,method,ate,ate_aligned,ego_anees). Development only.
set -euo pipefail
if [[ $# -lt 1 ]]; then
	sed -n '2,15p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/mrclam_loro}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
# find_exe, with_keys
source "$SRC/scripts/mrclam_variants.sh"
IMPORT=$(find_exe dynslam-mrclam)
COMPARE=$(find_exe dynslam-compare)
# INI $1 with the [MRCLAM_Import] keys of file $2 (key = value lines) replacing its own
merge_ini() {
	awk -F' *= *' 'FNR == NR { if ($0 ~ / = /) v[$1] = $2; next }
		/^\[/ { s = ($0 == "[MRCLAM_Import]") }
		s && ($1 in v) { print $1 " = " v[$1]; next } { print }' "$2" "$1"
}
mkdir -p "$OUT"
CSV="$OUT/loro.csv"
echo "robot,model,method,ate,ate_aligned,ego_anees" > "$CSV"
PARAMS="std_range std_bearing odo_delay odo_scale_v odo_std_xy_min odo_var_xy_per_m odo_var_xy_per_rad odo_std_phi_min odo_var_phi_per_m odo_var_phi_per_rad odo_tau_xy odo_tau_phi"
echo "left_out,${PARAMS// /,}" > "$OUT/params.csv"
for N in ${ROBOTS:-1 2 3 4 5}; do
	D="$OUT/robot$N"
	mkdir -p "$D"
	cp "$SRC/config/mrclam.ini" "$D/loro.ini"
	for P in $(seq 1 "${PASSES:-3}"); do
		"$IMPORT" --dataset "$DATA" --estimate-noise --all-robots --leave-out "$N" \
			--config "$D/loro.ini" --out "$D/pass$P" > "$D/pass$P.log"
		merge_ini "$D/loro.ini" "$D/pass$P/noise_estimate.ini" > "$D/loro.tmp"
		mv "$D/loro.tmp" "$D/loro.ini"
	done
	awk -F' *= *' -v p="$PARAMS" -v n="$N" 'BEGIN { k = split(p, a, " ") }
		/^\[/ { s = ($0 == "[MRCLAM_Import]") } s && NF == 2 { v[$1] = $2 }
		END { printf "%s", n; for (i = 1; i <= k; ++i) printf ",%s", v[a[i]]; print "" }' \
		"$D/loro.ini" >> "$OUT/params.csv"
	for MODEL in ${MODELS:-white inflated}; do
		mkdir -p "$D/$MODEL"
		printf 'odo_noise_model = %s\n' "$MODEL" > "$D/$MODEL/model.ini"
		merge_ini "$D/loro.ini" "$D/$MODEL/model.ini" > "$D/$MODEL/mrclam.ini"
		"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D/$MODEL" --config "$D/$MODEL/mrclam.ini" \
			> "$D/$MODEL/import.log"
		for M in ${METHODS:-gate huber}; do
			with_keys "outlier_method = $M" < "$SRC/config/mrclam_compare.ini" > "$D/$MODEL/$M.ini"
			"$COMPARE" -q -c "$D/$MODEL/$M.ini" -r "$D/$MODEL/robot$N.rawlog" --out "$D/$MODEL/$M" \
				--filters dynamic --no-figures > "$D/$MODEL/$M.log" 2>&1 ||
				{ echo "robot $N $MODEL $M: failed (see $D/$MODEL/$M.log)"; continue; }
			awk -F, -v r="$N" -v mo="$MODEL" -v m="$M" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
				{ print r "," mo "," m "," $c["ate"] "," $c["ate_aligned"] "," $c["ego_anees"] }' \
				"$D/$MODEL/$M/metrics.csv" >> "$CSV"
		done
	done
done
column -s, -t "$OUT/params.csv"
column -s, -t "$CSV"
