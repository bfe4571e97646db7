#!/usr/bin/env python3
"""Leave-one-sequence-out choice of [BoxTracker] min_score on imported detection rawlogs
(doc/boxes.md "Parameters"): runs dynslam-compare's rows tracker_baseline and default on every
sequence for each candidate, then, for each held-out sequence, picks the candidate with the
best pooled MOTA of `default` over the other sequences (the errors fn + fp + ids summed over them
divided by their truth boxes) and reports the pick and the held-out result.

  scripts/kitti_detections_grid.py IMPORT_DIR BUILD_DIR OUT_DIR VALUES...
IMPORT_DIR holds SSSS/kitti_SSSS.rawlog (scripts/kitti_detections.sh); VALUES e.g. none 0 2 4."""
import csv
import os
import subprocess
import sys

imp, build, out = sys.argv[1], sys.argv[2], sys.argv[3]
values = sys.argv[4:]
src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
compare = os.path.join(build, "apps/dynslam-compare/dynslam-compare")
seqs = sorted(d for d in os.listdir(imp) if os.path.isfile(os.path.join(imp, d, "kitti_%s.rawlog" % d)))
os.makedirs(out, exist_ok=True)
res = {}  # (value, seq, filter) -> row
for v in values:
    ini = os.path.join(src, "config", "_grid_%s.ini" % os.getpid())
    with open(ini, "w") as f:
        f.write("@include compare_kitti_detections.ini\n[BoxTracker]\n")
        # none: no threshold (below every score; the shipped INI's own value is overridden)
        f.write("min_score = %s\n" % ("-1e9" if v == "none" else v))
    try:
        for s in seqs:
            d = os.path.join(out, v, s)
            subprocess.run([compare, "-c", ini, "-r", os.path.join(imp, s, "kitti_%s.rawlog" % s),
                            "--out", d, "-q", "--no-figures", "--filters", "tracker_baseline,default"],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            for r in csv.DictReader(open(os.path.join(d, "metrics.csv"))):
                res[(v, s, r["filter"])] = r
    finally:
        os.remove(ini)


def errors(v, ss, flt):
    e = g = 0
    for s in ss:
        r = res[(v, s, flt)]
        e += int(r["fp"]) + int(r["fn"]) + int(r["ids"])
        g += int(r["gt"])
    return e, g


print("value," + ",".join("%s_%s" % (f, s) for s in seqs for f in ("base", "default")) + ",pooled_base,pooled_default")
for v in values:
    cells = []
    for s in seqs:
        for f in ("tracker_baseline", "default"):
            cells.append("%.4f" % float(res[(v, s, f)]["mota"]))
    eb, g = errors(v, seqs, "tracker_baseline")
    ed, _ = errors(v, seqs, "default")
    print(v + "," + ",".join(cells) + ",%.4f,%.4f" % (1 - eb / g, 1 - ed / g))
print()
print("held_out,picked,default_mota,baseline_mota_same_value")
for s in seqs:
    others = [x for x in seqs if x != s]
    best = min(values, key=lambda v: errors(v, others, "default")[0])
    print("%s,%s,%.4f,%.4f" % (s, best, float(res[(best, s, "default")]["mota"]),
                               float(res[(best, s, "tracker_baseline")]["mota"])))
