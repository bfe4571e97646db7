#!/usr/bin/env python3
"""The paper's filter (P, prior_gauge = prior) against the default profile (PA, the anchored
gauge) on the scenario families of issue 28, both ways: per seed the ratio of each one's ego
ATE to the other's (doc/results/profiles.md, "2026-11-29: P or PA on the Monte Carlo families").

  scripts/gauge_regret.py [RUNS_CSV]    (default: scripts/mm_families_runs.csv)

Prints a markdown table: per family the worst, 95th-percentile and median ratio of P to PA and
of PA to P, and both mean ATEs."""
import collections
import csv
import os
import statistics
import sys


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "mm_families_runs.csv")
    runs = collections.defaultdict(dict)
    with open(path) as f:
        for r in csv.DictReader(f):
            if not r["error"]:
                runs[(r["family"], r["seed"])][r["row"]] = float(r["ate"])
    fams = collections.OrderedDict()
    for (fam, _), d in runs.items():
        if "paper" in d and "default" in d:
            fams.setdefault(fam, []).append((d["paper"], d["default"]))
    print("| family | seeds | P / PA worst | p95 | median | PA / P worst | p95 | median "
          "| mean ATE P [m] | mean ATE PA [m] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for fam, v in fams.items():
        pa = sorted(p / a for p, a in v)
        ap = sorted(a / p for p, a in v)
        q = lambda x: x[int(0.95 * (len(x) - 1))]
        print(f"| {fam} | {len(v)} | {pa[-1]:.3f} | {q(pa):.3f} | {statistics.median(pa):.3f} "
              f"| {ap[-1]:.3f} | {q(ap):.3f} | {statistics.median(ap):.3f} "
              f"| {statistics.mean(p for p, _ in v):.4f} | {statistics.mean(a for _, a in v):.4f} |")


if __name__ == "__main__":
    main()
