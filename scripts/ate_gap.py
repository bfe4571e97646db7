#!/usr/bin/env python3
"""Ego ATE and NEES inside and outside a landmark gap (issue 13), from dynslam-compare's output.

    scripts/ate_gap.py OUT_DIR GT_BASE START END [FILTER ...]

OUT_DIR: a dynslam-compare --out folder (<filter>_ego.csv: step,...,x,y,...,nees); GT_BASE: the
ground truth base (e.g. datasets/tunnel: <base>_gt_ego.csv); START END: the gap in metres
along the road (the ground-truth ego x, highway). Prints, per filter, the unaligned ATE over
all steps, over the steps whose true ego x lies in [START, END] and over the others, the
error at the gap's last step (the drift accumulated through it), and the mean ego NEES
(3 dof per step) over the gap's steps with its two-sided 95 % chi-square bounds
(chi2(3 n) quantiles / n for n steps; one run, so the steps are not independent: a guide, not
a test). Definitions: doc/metrics.md "Inside a landmark gap".
"""
import csv
import math
import os
import sys


def read(path):
    with open(path) as f:
        return {int(r["step"]): (float(r["x"]), float(r["y"]), float(r.get("nees") or "nan"))
                for r in csv.DictReader(f)}


def chi2_cdf(x, k):
    """P(X <= x), X ~ chi2(k): regularized lower gamma P(k/2, x/2) by its series."""
    a, t = k / 2.0, x / 2.0
    if t <= 0:
        return 0.0
    term = total = 1.0 / a
    n = 0
    while term > 1e-17 * total:
        n += 1
        term *= t / (a + n)
        total += term
    return total * math.exp(-t + a * math.log(t) - math.lgamma(a))


def chi2_quantile(p, k):
    lo, hi = 0.0, k + 20.0 * math.sqrt(2.0 * k) + 50.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if chi2_cdf(mid, k) < p else (lo, mid)
    return 0.5 * (lo + hi)


def rms(v):
    return math.sqrt(sum(e * e for e in v) / len(v)) if v else float("nan")


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    out, gt_base, a, b = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    gt = read(gt_base + "_gt_ego.csv")
    filters = sys.argv[5:] or sorted(
        f[: -len("_ego.csv")] for f in os.listdir(out) if f.endswith("_ego.csv"))
    gap_steps = [k for k, (x, _, _) in gt.items() if a <= x <= b]
    last = max(gap_steps) if gap_steps else None
    n = len(gap_steps)
    lower = chi2_quantile(0.025, 3 * n) / n if n else float("nan")
    upper = chi2_quantile(0.975, 3 * n) / n if n else float("nan")
    print("filter,ate,ate_gap,ate_outside,err_gap_end,steps_gap,nees_gap,nees_gap_lower,"
          "nees_gap_upper")
    for f in filters:
        est = read(os.path.join(out, f + "_ego.csv"))
        err = {k: math.hypot(x - gt[k][0], y - gt[k][1]) for k, (x, y, _) in est.items()
               if k in gt}
        inside = [e for k, e in err.items() if k in gap_steps]
        outside = [e for k, e in err.items() if k not in gap_steps]
        end = err.get(last, float("nan")) if last is not None else float("nan")
        nees = [est[k][2] for k in gap_steps if k in est]
        mean_nees = sum(nees) / len(nees) if nees else float("nan")
        print("%s,%.4f,%.4f,%.4f,%.4f,%d,%.3f,%.3f,%.3f" % (
            f, rms(list(err.values())), rms(inside), rms(outside), end, len(inside), mean_nees,
            lower, upper))


if __name__ == "__main__":
    main()
