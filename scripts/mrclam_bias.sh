#!/usr/bin/env bash
# The odometry-bias comparison of doc/results/real-data.md 5.10 (issue 17 item 2): imports one MRCLAM
# dataset for each robot as ego and runs the dynamic EKF of config/mrclam_compare.ini with and
# without the odometry bias block, every other setting unchanged. The bias parameters are fixed
# here, before the runs, the same for every robot (doc/results/real-data.md 5.10 says why these).
#
#   scripts/mrclam_bias.sh DATASET_DIR [OUT_DIR] [BUILD_DIR]
#
# Writes OUT_DIR/robotN/<variant>/metrics.csv and OUT_DIR/variants.csv
# (robot,variant,ate,ate_aligned,ego_anees). Development only: no test needs it.
# VARIANTS (default "gate rate huber huber_rate"): gate = outlier_method = gate; rate = gate +
# odometry_bias = rate; rate_scale = gate + odometry_bias = rate_scale (scale prior std 5 %,
# random walk 0.001 / sqrt(s)); huber = outlier_method = huber; huber_rate = both. RATE_RW
# overrides bias_rate_rw. metrics.csv has the final bias (odometry_bias_*_final).
set -euo pipefail
if [[ $# -lt 1 ]]; then
	sed -n '2,14p' "$0"
	exit 1
fi
DATA=$1
OUT=${2:-out/mrclam_bias}
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${3:-$SRC/build}
# The bias parameters (fixed before the runs, doc/results/real-data.md 5.10): prior std 1 deg/s,
# random walk 0.17 deg/s per sqrt(s) (the bias may change by ~0.5 deg/s within 10 s),
# odometry_dt = 0.4 s (only for the first step: the actions carry timestamps).
# The bias block's keys are in their own section [OdometryBias] (doc/configuration.md): the
# variant's lines go to the top of [DynamicKFSLAM] (mrclam_variants.sh), so they open
# [OdometryBias] after the core keys and end by reopening [DynamicKFSLAM] for the lines after them.
BIAS_KEYS="odometry_bias = rate
[OdometryBias]
odometry_dt = 0.4
bias_rate_std0 = 0.0175
bias_rate_rw = ${RATE_RW:-0.003}"
TAG=variant
variant_keys() {
	local keys
	# the outlier method explicitly (config/mrclam_compare.ini ships huber since 5.13)
	if [[ $1 == huber* ]]; then
		keys="outlier_method = huber"
	else
		keys="outlier_method = gate"
	fi
	if [[ $1 == *rate_scale* ]]; then
		keys="$keys
${BIAS_KEYS/odometry_bias = rate/odometry_bias = rate_scale}
bias_scale_std0 = 0.05
bias_scale_rw = 0.001
[DynamicKFSLAM]"
	elif [[ $1 == *rate* ]]; then
		keys="$keys
$BIAS_KEYS
[DynamicKFSLAM]"
	fi
	echo "$keys"
}
source "$SRC/scripts/mrclam_variants.sh"
# shellcheck disable=SC2086
run_variants ${VARIANTS:-gate rate huber huber_rate}
