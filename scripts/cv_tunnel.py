#!/usr/bin/env python3
"""Tunnel ego ATE of object-model settings (doc/results/results.md 4.3.2).

Runs dynslam-compare once per setting on config/compare_tunnel.ini with the setting's
[DynamicKFSLAM] keys written over the INI's (filters = dynamic_cv only, no figures) and prints
one CSV row per setting: name, ego ATE and ego ATE inside the gap (metrics.csv's ate, ate_gap).
A setting is a line "name: key = value; key = value" (the format of scripts/cv_grid.py).

    scripts/cv_tunnel.py --bin build/apps/dynslam-compare/dynslam-compare --settings FILE --out OUT
"""
import argparse
import csv
import os
import subprocess
import sys

from cv_grid import parse_setting
from ini_sections import section_of, split_keys


def write_ini(base, keys, path):
    """base with keys written over [DynamicKFSLAM]'s and its modules' sections (ini_sections.py),
    paths made absolute, dynamic_cv only."""
    here = os.path.dirname(os.path.abspath(base))
    core, modules = split_keys({k: v for k, v in keys.items() if k != "object_model"})
    out, section = [], None
    for line in open(base):
        s = line.split("#")[0].strip()
        if s.startswith("["):
            section = s
        key = s.split("=", 1)[0].strip() if "=" in s else None
        if key in ("rawlog", "ground_truth") and section == "[Compare]":
            line = "%s = %s\n" % (key, os.path.join(here, s.split("=", 1)[1].strip()))
        elif key == "filters" and section == "[Compare]":
            line = "filters = dynamic_cv\n"
        elif key == "figures" and section == "[Compare]":
            line = "figures = false\n"
        elif key and section == "[%s]" % section_of(key) and key in keys:
            continue  # replaced below
        out.append(line)
        if s == "[DynamicKFSLAM]":
            out.extend("%s = %s\n" % kv for kv in core.items())
    out.append(modules)
    with open(path, "w") as f:
        f.writelines(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--settings", required=True)
    ap.add_argument("--base", default=os.path.join(os.path.dirname(__file__), "..", "config",
                                                   "compare_tunnel.ini"))
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    print("setting,ate,ate_gap")
    for line in open(a.settings):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        name, keys = parse_setting(line)
        if keys.get("object_model", "cv") != "cv":
            continue
        d = os.path.join(a.out, name)
        os.makedirs(d, exist_ok=True)
        ini = os.path.join(d, "compare.ini")
        write_ini(a.base, keys, ini)
        subprocess.run([a.bin, "-c", ini, "-o", d], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        row = next(r for r in csv.DictReader(open(os.path.join(d, "metrics.csv")))
                   if r["filter"] == "dynamic_cv")
        print("%s,%.4f,%.4f" % (name, float(row["ate"]), float(row["ate_gap"])))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
