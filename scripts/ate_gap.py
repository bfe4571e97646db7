#!/usr/bin/env python3
"""Ego ATE inside and outside a landmark gap (issue 13), from dynslam-compare's output.

    scripts/ate_gap.py OUT_DIR GT_BASE START END [FILTER ...]

OUT_DIR: a dynslam-compare --out folder (<filter>_ego.csv: step,...,x,y,...); GT_BASE: the
ground truth base (e.g. datasets/tunnel: <base>_gt_ego.csv); START END: the gap in metres
along the road (the ground-truth ego x, highway). Prints, per filter, the unaligned ATE over
all steps, over the steps whose true ego x lies in [START, END] and over the others, and the
error at the gap's last step (the drift accumulated through it).
"""
import csv
import math
import os
import sys


def read(path):
    with open(path) as f:
        return {int(r["step"]): (float(r["x"]), float(r["y"])) for r in csv.DictReader(f)}


def rms(v):
    return math.sqrt(sum(e * e for e in v) / len(v)) if v else float("nan")


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    out, gt_base, a, b = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    gt = read(gt_base + "_gt_ego.csv")
    filters = sys.argv[5:] or sorted(
        f[: -len("_ego.csv")] for f in os.listdir(out) if f.endswith("_ego.csv"))
    gap_steps = [k for k, (x, _) in gt.items() if a <= x <= b]
    last = max(gap_steps) if gap_steps else None
    print("filter,ate,ate_gap,ate_outside,err_gap_end,steps_gap")
    for f in filters:
        est = read(os.path.join(out, f + "_ego.csv"))
        err = {k: math.hypot(x - gt[k][0], y - gt[k][1]) for k, (x, y) in est.items() if k in gt}
        inside = [e for k, e in err.items() if k in gap_steps]
        outside = [e for k, e in err.items() if k not in gap_steps]
        end = err.get(last, float("nan")) if last is not None else float("nan")
        print("%s,%.4f,%.4f,%.4f,%.4f,%d" % (f, rms(list(err.values())), rms(inside), rms(outside),
                                            end, len(inside)))


if __name__ == "__main__":
    main()
