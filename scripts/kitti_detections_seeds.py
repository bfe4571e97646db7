#!/usr/bin/env python3
"""How much of `default` vs `odometry` on the detector-box sequences is the odometry's noise
realisation (doc/boxes.md "Targets of the issue"): imports each sequence once per odometry-noise
seed ([KITTI_Import] seed over config/kitti_detections.ini: the same boxes and truth, another
draw of the odometry noise), runs dynslam-compare's rows odometry and default on each, and
prints per sequence the ego ATE of both rows per seed, their means, the mean ego ANEES of both
and how often default <= odometry. Development only: no test needs it.

  scripts/kitti_detections_seeds.py DATA_DIR DET_DIR OUT_DIR BUILD_DIR SEED [SEED ...]
DATA_DIR: label_02/ and poses/; DET_DIR: the detector's folder (CLASS/SSSS.txt; calib beside it
or inside, as scripts/kitti_detections.sh); KITTI_INI=FILE replaces
config/compare_kitti_detections.ini; SEQUENCES="0000 ..." (default 0000-0010)."""
import csv
import os
import subprocess
import sys

if len(sys.argv) < 6:
    sys.exit(__doc__)
data, det, out, build = (os.path.abspath(a) for a in sys.argv[1:5])
seeds = [int(s) for s in sys.argv[5:]]
src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
seqs = os.environ.get("SEQUENCES", " ".join("%04d" % i for i in range(11))).split()
ini = os.environ.get("KITTI_INI", os.path.join(src, "config", "compare_kitti_detections.ini"))
calib = os.path.join(os.path.dirname(det), "calib")
if not os.path.isdir(calib):
    calib = os.path.join(det, "calib")
kitti = os.path.join(build, "apps/dynslam-kitti/dynslam-kitti")
compare = os.path.join(build, "apps/dynslam-compare/dynslam-compare")
os.makedirs(out, exist_ok=True)
res = {}  # (seq, seed) -> {filter: row}
for n in seeds:
    imp_ini = os.path.join(out, "import_seed%d.ini" % n)
    with open(imp_ini, "w") as f:
        f.write("@include %s\n[KITTI_Import]\nseed = %d\n" %
                (os.path.join(src, "config", "kitti_detections.ini"), n))
    for s in seqs:
        d = os.path.join(out, "seed%d" % n, s)
        subprocess.run([kitti, "--labels", os.path.join(data, "label_02"), "--poses",
                        os.path.join(data, "poses"), "--sequence", s, "--out", d, "-c", imp_ini,
                        "--detections", det, "--calib", calib],
                       check=True, stdout=subprocess.DEVNULL)
        subprocess.run([compare, "-c", ini, "-r", os.path.join(d, "kitti_%s.rawlog" % s), "--out",
                        os.path.join(d, "compare"), "-q", "--no-figures", "--filters",
                        "odometry,default"], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        rows = csv.DictReader(open(os.path.join(d, "compare", "metrics.csv")))
        res[(s, n)] = {r["filter"]: r for r in rows}


def mean(x):
    return sum(x) / len(x)


print("| seq | " + " | ".join("seed %d" % n for n in seeds) +
      " | mean ATE default / odometry | mean ANEES default / odometry | default <= odometry |")
print("|---" * (len(seeds) + 4) + "|")
wins_total = 0
for s in seqs:
    ate = {f: [float(res[(s, n)][f]["ate"]) for n in seeds] for f in ("default", "odometry")}
    anees = {f: [float(res[(s, n)][f]["ego_anees"]) for n in seeds] for f in ("default", "odometry")}
    wins = sum(a <= b for a, b in zip(ate["default"], ate["odometry"]))
    wins_total += wins
    cells = ["%.2f / %.2f" % (a, b) for a, b in zip(ate["default"], ate["odometry"])]
    print("| %s | %s | %.2f / %.2f | %.2f / %.2f | %d of %d |" %
          (s, " | ".join(cells), mean(ate["default"]), mean(ate["odometry"]),
           mean(anees["default"]), mean(anees["odometry"]), wins, len(seeds)))
print("\ndefault <= odometry in %d of %d runs" % (wins_total, len(seqs) * len(seeds)))
