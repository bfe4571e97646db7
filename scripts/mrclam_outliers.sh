#!/usr/bin/env bash
# The outlier-method comparison of doc/results/real-data.md 5.9 (issue 17): imports one MRCLAM dataset
# for each robot as ego and runs the dynamic EKF of config/mrclam_compare.ini once per
# outlier_method, every other setting unchanged (the method's parameters are the defaults).
#
#   scripts/mrclam_outliers.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
# Writes OUT_DIR/robotN/<method>/metrics.csv and OUT_DIR/methods.csv
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
TAG=method
# "shipped": config/mrclam_compare.ini unchanged (its own outlier_method)
variant_keys() { [[ $1 == shipped ]] || echo "outlier_method = $1"; }
source "$SRC/scripts/mrclam_variants.sh"
# shellcheck disable=SC2086
run_variants ${METHODS:-gate none huber cauchy gate_recovery jcbb}
