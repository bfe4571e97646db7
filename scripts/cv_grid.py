#!/usr/bin/env python3
"""Mean ego ATE per Table I level of object-model settings (doc/results/results.md 4.3).

Runs dynslam-montecarlo once per setting on config/montecarlo.ini with the setting's
[DynamicKFSLAM] keys added, and prints one CSV row per setting: its name and the mean over the
runs of the ego ATE at each level. A setting is a line "name: key = value; key = value".

    scripts/cv_grid.py --bin build/apps/dynslam-montecarlo --settings FILE --seed 500000 \
        --runs 8 --out OUT [--levels all] [--threads 1]

--seed is the base noise seed of dynslam-montecarlo (run r at level L: seed + 1000 L + r): the
Table I runs of doc/results/results.md section 2 use seed 1 and 25 runs (seeds 1..8025); a development
set must use a base whose seeds do not meet them (e.g. 500000).
"""
import argparse
import csv
import os
import subprocess
import sys

from ini_sections import split_keys

LEVELS = ["w1v1", "w1v2", "w1v3", "w2v1", "w2v2", "w2v3", "w3v1", "w3v2", "w3v3"]


def write_ini(base, keys, path):
    """base INI with keys added at the top of [DynamicKFSLAM] (a module's keys in its own section
    at the end, ini_sections.py); the scenario path made absolute."""
    core, modules = split_keys(keys)
    here = os.path.dirname(os.path.abspath(base))
    out = []
    for line in open(base):
        s = line.split("#")[0].strip()
        if s.startswith("scenario") and "=" in s:
            name = s.split("=", 1)[1].strip()
            line = "scenario = " + os.path.join(here, name) + "\n"
        key = s.split("=", 1)[0].strip() if "=" in s else None
        if key and key in keys:
            continue  # replaced below
        out.append(line)
        if s == "[DynamicKFSLAM]":
            out.extend("%s = %s\n" % kv for kv in core.items())
    out.append(modules)
    with open(path, "w") as f:
        f.writelines(out)


def parse_setting(line):
    name, _, rest = line.partition(":")
    keys = {}
    for kv in rest.split(";"):
        if kv.strip():
            k, _, v = kv.partition("=")
            keys[k.strip()] = v.strip()
    return name.strip(), keys


def mean_ate(runs_csv):
    acc = {}
    with open(runs_csv) as f:
        for row in csv.DictReader(f):
            acc.setdefault(row["level"], []).append(float(row["ate"]))
    return {lv: sum(v) / len(v) for lv, v in acc.items()}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--settings", required=True)
    ap.add_argument("--base", default=os.path.join(os.path.dirname(__file__), "..", "config",
                                                   "montecarlo.ini"))
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--runs", type=int, required=True)
    ap.add_argument("--levels", default="all")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    levels = LEVELS if a.levels == "all" else a.levels.split(",")
    print("setting," + ",".join(levels))
    for line in open(a.settings):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        name, keys = parse_setting(line)
        d = os.path.join(a.out, name)
        os.makedirs(d, exist_ok=True)
        ini = os.path.join(d, "montecarlo.ini")
        write_ini(a.base, keys, ini)
        subprocess.run([a.bin, "-c", ini, "--seed", str(a.seed), "--runs", str(a.runs),
                        "--levels", a.levels, "--threads", str(a.threads), "--no-figures",
                        "-q", "--out", d], check=True, stdout=subprocess.DEVNULL)
        m = mean_ate(os.path.join(d, "runs.csv"))
        print(name + "," + ",".join("%.4f" % m[lv] for lv in levels))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
