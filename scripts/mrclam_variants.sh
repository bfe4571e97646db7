# Sourced by scripts/mrclam_outliers.sh and scripts/mrclam_bias.sh (not run by itself): imports
# one MRCLAM dataset for each robot as ego and runs the dynamic EKF of config/mrclam_compare.ini
# once per variant, each variant being extra [DynamicKFSLAM] keys (everything else as shipped).
# The caller sets DATA, OUT, SRC, BUILD, TAG (the CSV's second column name and file name) and
# defines variant_keys NAME (prints the variant's keys), then calls run_variants V1 V2 ...
# Writes OUT/robotN/<variant>/metrics.csv and OUT/<TAG>s.csv (robot,TAG,ate,ate_aligned,ego_anees).
find_exe() {
	local p
	p=$(find "$BUILD" -type f -perm -u+x -name "$1" 2>/dev/null | head -n 1)
	[[ -n "$p" ]] || { echo "$(basename "$0"): $1 not found under $BUILD" >&2; exit 1; }
	echo "$p"
}
# Copies stdin to stdout with the key = value lines of $1 at the top of [DynamicKFSLAM], and
# that section's own lines for the same keys dropped (the shipped outlier_method, e.g.).
with_keys() {
	awk -v k="$1" 'BEGIN { n = split(k, L, "\n"); for (i = 1; i <= n; ++i) { split(L[i], kv, / *= */); K[kv[1]] = 1 } }
		/^\[/ { s = ($0 == "[DynamicKFSLAM]") }
		s && !/^\[/ { split($0, kv, / *= */); if (kv[1] in K) next }
		{ print } /^\[DynamicKFSLAM\]$/ && k != "" { print k }'
}
run_variants() {
	local IMPORT COMPARE CSV N D V keys
	IMPORT=$(find_exe dynslam-mrclam)
	COMPARE=$(find_exe dynslam-compare)
	CSV="$OUT/${TAG}s.csv"
	mkdir -p "$OUT"
	echo "robot,$TAG,ate,ate_aligned,ego_anees" > "$CSV"
	for N in ${ROBOTS:-1 2 3 4 5}; do
		D="$OUT/robot$N"
		mkdir -p "$D"
		[[ -s "$D/robot$N.rawlog" ]] ||
			"$IMPORT" --dataset "$DATA" --robot "$N" --out "$D" --config "$SRC/config/mrclam.ini" \
				> "$D/import.log"
		for V in "$@"; do
			keys=$(variant_keys "$V")
			with_keys "$keys" < "$SRC/config/mrclam_compare.ini" > "$D/$V.ini"
			"$COMPARE" -q -c "$D/$V.ini" -r "$D/robot$N.rawlog" --out "$D/$V" --filters dynamic \
				--no-figures > "$D/$V.log" 2>&1 || { echo "robot $N $V: failed (see $D/$V.log)"; continue; }
			awk -F, -v r="$N" -v m="$V" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
				{ print r "," m "," $c["ate"] "," $c["ate_aligned"] "," $c["ego_anees"] }' \
				"$D/$V/metrics.csv" >> "$CSV"
		done
	done
	column -s, -t "$CSV"
}
