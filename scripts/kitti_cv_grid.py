#!/usr/bin/env python3
"""Object-model settings on imported KITTI sequences (doc/kitti.md 5.6; development tool).

Runs dynslam-kitti-report once per setting and sequence on config/compare_kitti.ini with the
setting's [DynamicKFSLAM] keys added, filters dynamic_cv and dynamic_ctrv (--filters), and
prints one CSV row per setting, model and sequence: ego ATE, ego ANEES, object position RMSE,
object speed RMSE (all steps, and the steps where the object is read), and the setting's ratio to the paper's filter (--baseline: a summary.csv of
the same sequences with the row "dynamic", e.g. from scripts/kitti_results.sh). A setting is a
line "name: key = value; key = value".

    scripts/kitti_cv_grid.py --bin build/tests/kitti/dynslam-kitti-report --imports OUT \\
        --sequences 0000,0001,0002,0003,0004 --settings FILE --out GRID [--baseline CSV]

--imports holds SSSS/kitti_SSSS.rawlog (+ ground truth) written by dynslam-kitti
(scripts/kitti_results.sh writes that layout). The sequences used to choose are the development
set; report the held-out ones once, with the frozen setting.
"""
import argparse
import csv
import os
import subprocess
import sys

from cv_grid import parse_setting, write_ini  # the same INI writer and setting format

HERE = os.path.dirname(os.path.abspath(__file__))
BASE_INI = os.path.join(HERE, "..", "config", "compare_kitti.ini")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--imports", required=True)
    ap.add_argument("--sequences", default="0000,0001,0002,0003,0004")
    ap.add_argument("--settings", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--filters", default="dynamic_cv,dynamic_ctrv")
    ap.add_argument("--baseline", help="summary.csv with the rows 'dynamic' of the sequences")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    base = {}
    if a.baseline:
        for r in csv.DictReader(open(a.baseline)):
            if r["filter"] == "dynamic":
                base[r["label"]] = float(r["ate"])
    w = csv.writer(sys.stdout)
    w.writerow(["setting", "filter", "seq", "ate", "ate_ratio_dynamic", "ego_anees",
                "obj_pos_rmse", "obj_speed_rmse", "obj_velocity_anees", "obj_pos_rmse_seen",
                "obj_speed_rmse_seen"])
    for line in open(a.settings):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        name, keys = parse_setting(line)
        ini = os.path.join(a.out, name + ".ini")
        write_ini(BASE_INI, keys, ini)
        for s in a.sequences.split(","):
            d = os.path.join(a.out, name, s)
            raw = os.path.join(a.imports, s, "kitti_%s.rawlog" % s)
            subprocess.run([a.bin, "-c", ini, "-r", raw, "--out", d, "--label", s,
                            "--filters", a.filters], check=True, stdout=subprocess.DEVNULL)
            for r in csv.DictReader(open(os.path.join(d, "summary.csv"))):
                if r["filter"] == "odometry":
                    continue
                ate = float(r["ate"])
                ratio = ate / base[s] if s in base else float("nan")
                w.writerow([name, r["filter"], s, "%.4f" % ate, "%.3f" % ratio,
                            r["ego_anees"], r["obj_pos_rmse"], r["obj_speed_rmse"],
                            r["obj_velocity_anees"], r["obj_pos_rmse_seen"],
                            r["obj_speed_rmse_seen"]])
                sys.stdout.flush()


if __name__ == "__main__":
    main()
