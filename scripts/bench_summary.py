#!/usr/bin/env python3
"""Summarizes dynslam-bench JSON output (scripts/bench.sh): medians (real and CPU time),
per-step times and the side-by-side ratios to CRangeBearingKFSLAM2D, as Markdown."""
import json
import sys

d = json.load(open(sys.argv[1]))
ctx = d["context"]
med = {}
for b in d["benchmarks"]:
    if b.get("aggregate_name") == "median":
        med[b["run_name"]] = b
print(f"host {ctx.get('host_name')}, {ctx.get('num_cpus')} CPUs at {ctx.get('mhz_per_cpu')} MHz, "
      f"load average {ctx.get('load_avg')}, {ctx.get('date')}\n")
print("| benchmark | label | median real | median CPU | unit | counters |")
print("|---|---|---|---|---|---|")
skip = {"name", "run_name", "run_type", "repetitions", "threads", "aggregate_name", "iterations",
        "real_time", "cpu_time", "time_unit", "label", "family_index", "per_family_instance_index",
        "repetition_index", "aggregate_unit"}
for name, b in med.items():
    counters = ", ".join(f"{k}={b[k]:.4g}" for k in b if k not in skip and isinstance(b[k], (int, float)))
    print(f"| {name} | {b.get('label', '')} | {b['real_time']:.4g} | {b['cpu_time']:.4g} | "
          f"{b['time_unit']} | {counters} |")

def ratio(a, b, key):
    if a in med and b in med:
        return med[a][key] / med[b][key]
    return float("nan")

print("\nSide by side (same process, same static-only run), ratio of medians to CRangeBearingKFSLAM2D:\n")
print("| landmarks | update | per-step CPU [ms] | ratio (CPU) | ratio (real) |")
print("|---|---|---|---|---|")
for n in (80, 400):
    base = f"BM_StaticRun/0/{n}"
    if base not in med:
        continue
    steps = med[base].get("steps", 121)
    for f, lab in ((0, "CRangeBearingKFSLAM2D"), (1, "dynamic, mrpt"), (2, "dynamic, sparse")):
        name = f"BM_StaticRun/{f}/{n}"
        if name in med:
            print(f"| {n} | {lab} | {med[name]['cpu_time'] / steps:.4g} | "
                  f"{ratio(name, base, 'cpu_time'):.3f} | {ratio(name, base, 'real_time'):.3f} |")
