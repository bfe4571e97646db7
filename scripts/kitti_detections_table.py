#!/usr/bin/env python3
"""The table of doc/boxes.md from scripts/kitti_detections.sh's output folder: per sequence and
row, ego ATE and ANEES, and MOTA / IDS / FP / FN (Car, BEV IoU 0.25), sAMOTA, and the checks of
issue 31's targets (default vs tracker_baseline, static_all and odometry). Also writes
OUT/summary.csv. Usage: kitti_detections_table.py OUT SEQ [SEQ ...]"""
import csv
import sys


def f(x, d=3):
    try:
        return ("%." + str(d) + "f") % float(x)
    except (TypeError, ValueError):
        return "-"


COLS = ["sequence", "filter", "ate", "ate_aligned", "ego_anees", "mota", "motp", "ids", "frag",
        "fp", "fn", "gt", "samota", "mota_d2", "motp_d2", "ids_d2", "ms_per_step"]
rows = []
for s in sys.argv[2:]:
    try:
        for r in csv.DictReader(open("%s/%s/compare/metrics.csv" % (sys.argv[1], s))):
            r["sequence"] = s
            rows.append(r)
    except FileNotFoundError:
        pass
with open(sys.argv[1] + "/summary.csv", "w") as out:
    out.write(",".join(COLS) + "\n")
    for r in rows:
        out.write(",".join(r.get(c) or "" for c in COLS) + "\n")
seqs = sorted({r["sequence"] for r in rows})
by = {(r["sequence"], r["filter"]): r for r in rows}
print("| seq | row | ATE [m] | ego ANEES | MOTA | MOTP (IoU) | IDS | FRAG | FP | FN | sAMOTA | MOTA (2 m) | ms/step |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for s in seqs:
    for name in ("static_all", "odometry", "tracker_baseline", "default"):
        r = by.get((s, name))
        if not r:
            continue
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            s, name, f(r.get("ate")), f(r.get("ego_anees"), 2), f(r.get("mota"), 4),
            f(r.get("motp")), r.get("ids") or "-", r.get("frag") or "-", r.get("fp") or "-",
            r.get("fn") or "-", f(r.get("samota"), 4), f(r.get("mota_d2"), 4),
            f(r.get("ms_per_step"))))
print()
print("| seq | default MOTA >= baseline | default IDS <= baseline | ATE <= static_all | ATE <= odometry | ANEES <= 10 |")
print("|---|---|---|---|---|---|")
for s in seqs:
    d, b = by.get((s, "default")), by.get((s, "tracker_baseline"))
    st, od = by.get((s, "static_all")), by.get((s, "odometry"))
    if not d:
        continue

    def cmp(a, op, c, key):
        try:
            x, y = float(a[key]), float(c[key])
        except (TypeError, ValueError, KeyError):
            return "-"
        ok = x >= y if op == ">=" else x <= y
        return ("yes" if ok else "**no**") + " (%s vs %s)" % (f(x, 4), f(y, 4))
    anees = d.get("ego_anees")
    ok = "-" if not anees else ("yes" if float(anees) <= 10 else "**no**") + " (%s)" % f(anees, 2)
    print("| %s | %s | %s | %s | %s | %s |" % (
        s, cmp(d, ">=", b, "mota") if b else "-", cmp(d, "<=", b, "ids") if b else "-",
        cmp(d, "<=", st, "ate") if st else "-", cmp(d, "<=", od, "ate") if od else "-", ok))
