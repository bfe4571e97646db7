#!/usr/bin/env python3
"""The choice of config/profiles/default.ini (doc/results/profiles.md): a leave-one-dataset-out
selection among a few candidate [DynamicKFSLAM] configurations over the development data.

  scripts/profile_campaign.py --data DIR [--build BUILD] [--out OUT] [--datasets a,b,...]
                              [--table-only]

DIR holds MRCLAM_Dataset6/ and KITTI_tracking_birdseye/ (development only: no test reads it).
Datasets: highway, tunnel, turning, manoeuvres (the shipped simulated rawlogs with their compare
INIs),
mrclam (MRCLAM Dataset 6, robots 1-5 as ego, config/mrclam_compare.ini), kitti (KITTI tracking
0000-0010, config/compare_kitti.ini). Every candidate runs as the `dynamic` row of
dynslam-compare on each run of each dataset (its keys appended to the run's INI: MRPT keeps the
last value of a repeated key). The score of a candidate on a dataset is its worst ratio, over
the dataset's runs, of the ego ATE to the paper's filter (candidate P) on the same run; a
candidate is chosen by its worst score over the datasets it is chosen on (ties within 0.005 by
the mean score). Leave-one-dataset-out: for each dataset, the candidate chosen on the others
and its score on the held-out one. One pass, one seed (the data are fixed recordings or the
shipped simulated rawlogs). Writes OUT/ate.csv (every run), OUT/table.md, and prints them.
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import time

from ini_sections import split_keys

SRC = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONFIG = os.path.join(SRC, "config")

# The candidates (at most four existing configurations; doc/results/profiles.md). cv_dt is a
# data key (the step length), added per dataset.
E_KEYS = {
    "object_model": "cv",
    "cv_accel_psd": "[1e-7 1e-7 1e-9]",
    "cv_velocity_prior_std": "[0.5 0.5 0.05]",
    "cv_gate": "0.999",
    "cv_fallback_steps": "0",
    "prior_gauge": "anchor",
}
CANDIDATES = {
    "P": {"object_model": "paper", "prior_gauge": "prior"},
    "PA": {"object_model": "paper", "prior_gauge": "anchor"},
    "E": E_KEYS,
    "E3": dict(E_KEYS, cv_fallback_steps="3"),
    # issue 28: E with multiple-model objects (mm's own keys at their defaults)
    "EM": dict(E_KEYS, object_model="mm"),
    "EM3": dict(E_KEYS, object_model="mm", cv_fallback_steps="3"),
    # mm with the library's default cv noise (nothing tuned on a dataset)
    "M": {"object_model": "mm", "cv_gate": "0.999", "prior_gauge": "anchor"},
}
CV_DT = {"highway": "0.5", "tunnel": "0.5", "turning": "0.5", "manoeuvres": "0.5", "mrclam": "0.4",
         "kitti": "0.1"}
KITTI_SEQS = ["%04d" % i for i in range(11)]


def find_exe(build, name):
    own = os.path.join(build, "apps", name, name)  # not an installed copy (tests/consumer)
    if os.access(own, os.X_OK):
        return own
    for root, _, files in os.walk(build):
        if name in files and os.access(os.path.join(root, name), os.X_OK):
            return os.path.join(root, name)
    sys.exit("profile_campaign.py: %s not found under %s (build it first)" % (name, build))


def absolute_paths(text, folder):
    """The INI text with its [Compare] rawlog / ground_truth / scenario paths made absolute."""
    out = []
    for line in text.splitlines():
        inc = re.match(r"^(\s*@include\s+)(\S+)(.*)$", line)
        if inc and not os.path.isabs(inc.group(2)):
            line = inc.group(1) + os.path.normpath(os.path.join(folder, inc.group(2))) + inc.group(3)
        m = re.match(r"^(\s*(rawlog|ground_truth|scenario)\s*=\s*)(\S+)(.*)$", line)
        if m and m.group(3) not in ("auto", "none", "false") and not os.path.isabs(m.group(3)):
            line = m.group(1) + os.path.normpath(os.path.join(folder, m.group(3))) + m.group(4)
        out.append(line)
    return "\n".join(out) + "\n"


def runs_of(dataset, out, data, exe):
    """(run label, base INI, rawlog or None) of a dataset; imports the real data once."""
    if dataset == "highway":
        return [("highway", os.path.join(CONFIG, "compare_highway.ini"), None)]
    if dataset == "tunnel":
        return [("tunnel", os.path.join(CONFIG, "compare_tunnel.ini"), None)]
    if dataset == "turning":
        return [("turning", os.path.join(CONFIG, "compare_turning_braking.ini"), None)]
    if dataset == "manoeuvres":
        return [("manoeuvres", os.path.join(CONFIG, "compare_tunnel_manoeuvres.ini"), None)]
    runs = []
    if dataset == "mrclam":
        for n in range(1, 6):
            d = os.path.join(out, "import", "mrclam", "robot%d" % n)
            rl = os.path.join(d, "robot%d.rawlog" % n)
            if not os.path.exists(rl):
                subprocess.run([exe("dynslam-mrclam"), "--dataset",
                                os.path.join(data, "MRCLAM_Dataset6"), "--robot", str(n),
                                "--out", d, "--config", os.path.join(CONFIG, "mrclam.ini")],
                               check=True, stdout=subprocess.DEVNULL)
            runs.append(("robot%d" % n, os.path.join(CONFIG, "mrclam_compare.ini"), rl))
        return runs
    if dataset == "kitti":
        k = os.path.join(data, "KITTI_tracking_birdseye")
        for s in KITTI_SEQS:
            d = os.path.join(out, "import", "kitti", s)
            rl = os.path.join(d, "kitti_%s.rawlog" % s)
            if not os.path.exists(rl):
                subprocess.run([exe("dynslam-kitti"), "--labels", os.path.join(k, "label_02"),
                                "--poses", os.path.join(k, "poses"), "--sequence", s, "--out", d,
                                "-c", os.path.join(CONFIG, "kitti.ini")],
                               check=True, stdout=subprocess.DEVNULL)
            runs.append(("kitti" + s, os.path.join(CONFIG, "compare_kitti.ini"), rl))
        return runs
    sys.exit("unknown dataset " + dataset)


def run_one(exe, dataset, label, base, rawlog, cand, out):
    keys = dict(CANDIDATES[cand])
    if keys.get("object_model") in ("cv", "mm"):
        keys["cv_dt"] = CV_DT[dataset]
    ini_dir = os.path.join(out, "ini")
    os.makedirs(ini_dir, exist_ok=True)
    ini = os.path.join(ini_dir, "%s_%s.ini" % (label, cand))
    with open(base) as f:
        text = absolute_paths(f.read(), os.path.dirname(base))
    core, modules = split_keys(keys)  # a module's keys in its own section (ini_sections.py)
    text += "\n[DynamicKFSLAM]\n" + "".join("%s = %s\n" % kv for kv in core.items()) + modules
    with open(ini, "w") as f:
        f.write(text)
    od = os.path.join(out, "runs", label, cand)
    cmd = [exe("dynslam-compare"), "-q", "-c", ini, "--filters", "dynamic", "--no-figures",
           "--out", od]
    if rawlog:
        cmd += ["-r", rawlog]
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print("FAILED %s %s: %s" % (label, cand, p.stdout[-400:]), file=sys.stderr)
        return float("nan"), time.time() - t0
    with open(os.path.join(od, "metrics.csv")) as f:
        rows = [r for r in csv.DictReader(f) if r["filter"] == "dynamic"]
    return float(rows[0]["ate"]), time.time() - t0


def choose(scores, names, datasets):
    """The candidate with the smallest worst score over `datasets` (ties within 0.005: mean)."""
    def key(c):
        v = [scores[d][c] for d in datasets]
        return max(v), sum(v) / len(v)
    best = min(names, key=key)
    ties = [c for c in names if key(c)[0] <= key(best)[0] + 0.005]
    return min(ties, key=lambda c: key(c)[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", required=True)
    ap.add_argument("--build", default=os.path.join(SRC, "build"))
    ap.add_argument("--out", default=os.path.join(SRC, "out", "profile_campaign"))
    ap.add_argument("--datasets", default="highway,tunnel,turning,manoeuvres,mrclam,kitti")
    ap.add_argument("--candidates", default=",".join(CANDIDATES))
    ap.add_argument("--table-only", action="store_true", help="only rebuild the table from ate.csv")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    exe = lambda n: find_exe(a.build, n)
    datasets = a.datasets.split(",")
    cands = a.candidates.split(",")
    csv_path = os.path.join(a.out, "ate.csv")
    done = {}
    if os.path.exists(csv_path):
        with open(csv_path) as f:
            for r in csv.DictReader(f):
                done[(r["dataset"], r["run"], r["candidate"])] = float(r["ate"])
    if not a.table_only:
        new = not os.path.exists(csv_path)
        with open(csv_path, "a", newline="") as f:
            w = csv.writer(f)
            if new:
                w.writerow(["dataset", "run", "candidate", "ate", "seconds"])
            for d in datasets:
                for label, base, rawlog in runs_of(d, a.out, a.data, exe):
                    for c in cands:
                        if (d, label, c) in done:
                            continue
                        ate, sec = run_one(exe, d, label, base, rawlog, c, a.out)
                        done[(d, label, c)] = ate
                        w.writerow([d, label, c, "%.6f" % ate, "%.1f" % sec])
                        f.flush()
                        print("%-8s %-10s %-3s ATE %.4f m (%.0f s)" % (d, label, c, ate, sec))
    # Scores: the worst ratio to P over a dataset's runs.
    scores, table = {}, []
    for d in datasets:
        labels = sorted({r for (dd, r, _) in done if dd == d})
        scores[d] = {}
        for c in cands:
            ratios = [done[(d, r, c)] / done[(d, r, "P")] for r in labels
                      if (d, r, c) in done and (d, r, "P") in done and done[(d, r, "P")] > 0]
            scores[d][c] = max(ratios) if ratios else float("nan")
        table.append((d, labels))
    lines = ["| dataset (runs) | " + " | ".join(cands) + " |",
             "|---|" + "---|" * len(cands)]
    for d, labels in table:
        lines.append("| %s (%d) | " % (d, len(labels)) +
                     " | ".join("%.3f" % scores[d][c] for c in cands) + " |")
    lines += ["", "| held out | chosen on the others | its score there | best there |",
              "|---|---|---|---|"]
    for d in datasets:
        others = [x for x in datasets if x != d]
        c = choose(scores, cands, others)
        best = min(cands, key=lambda x: scores[d][x])
        lines.append("| %s | %s | %.3f | %s (%.3f) |" % (d, c, scores[d][c], best, scores[d][best]))
    lines += ["", "chosen on all datasets: **%s**" % choose(scores, cands, datasets)]
    text = "\n".join(lines)
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write(text + "\n")
    print(text)


if __name__ == "__main__":
    main()
