#!/usr/bin/env python3
"""Issue 28's targets over scenario families and seeds (doc/results/multiple_model.md;
development tool, no test needs it).

  scripts/mm_families.py --out OUT [--build BUILD] [--seeds 50] [--seed0 3000] [--jobs 2]
                         [--level-seeds N] [--families tunnel,manoeuvres,...] [--keep]
                         [--table-only]

For each family and seed s = seed0 .. seed0 + seeds - 1: dynslam-simulate the family's
scenario INI with --noise-seed s (and --world-seed s, except the paper's highway, whose world
stays the one of config/highway.ini), then dynslam-compare on it with
config/compare_tunnel.ini's filter keys (setting E: cv_accel_psd = [1e-7 1e-7 1e-9],
cv_gate = 0.999, the anchored gauge; noise from the scenario) in two runs:
  - rows static_landmarks_only, dynamic_cv (cv), dynamic_mm (mm), default (the default profile);
  - row dynamic with prior_gauge = prior: the paper's filter (profiles/paper.ini, candidate P of
    scripts/profile_campaign.py), the reference of the ratios.
The family `markov` (config/tunnel_markov.ini, the model-matched truth of mm) also runs mm with
the truth's own mode keys (config/compare_tunnel_markov.ini, row mm_matched) for the NEES of the
ego and of the object poses against the 95 % bounds. Families `highway_<level>`: the paper's
highway (config/highway.ini) at the nine Table I noise levels (--noise).

Writes OUT/runs.csv (family, seed, row, ate, ego_anees, obj_pose_anees, ...), OUT/summary.md
(per family and row: seeds, mean ATE, % of seeds with ATE <= 1.05 x the paper's filter, worst
and median ratio, mean and max ego ANEES; the targets of issue 28 for the default profile) and
OUT/markov_nees.md. At most --jobs processes at a time; per-seed folders are removed unless
--keep.
"""
import argparse
import concurrent.futures as cf
import csv
import math
import os
import shutil
import statistics as st
import subprocess
import sys
import time

from ini_sections import split_keys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONFIG = os.path.join(ROOT, "config")
LEVELS = ["w%dv%d" % (w, v) for w in (1, 2, 3) for v in (1, 2, 3)]
# family -> (scenario INI, vary the world seed, noise level or None)
FAMILIES = {
    "tunnel": ("tunnel.ini", True, None),
    "manoeuvres": ("tunnel_manoeuvres.ini", True, None),
    "braking": ("tunnel_braking.ini", True, None),
    "stop_and_go": ("tunnel_stop_and_go.ini", True, None),
    "accel": ("tunnel_accel.ini", True, None),
    "markov": ("tunnel_markov.ini", True, None),
    "cutins": ("highway_cutins.ini", True, None),
    "turning_braking": ("generated_turning_braking.ini", True, None),
    "circle": ("circle_road.ini", True, None),
    "circle_no_landmarks": ("circle_road_no_landmarks.ini", True, None),
}
for _lvl in LEVELS:
    FAMILIES["highway_" + _lvl] = ("highway.ini", False, _lvl)
ROW_NAMES = {"dynamic": "paper", "dynamic_cv": "cv", "dynamic_mm": "mm", "default": "default",
             "static_landmarks_only": "static_landmarks_only"}
ROWS = ["paper", "cv", "mm", "default"]


def find_exe(build, name):
    p = os.path.join(build, "apps", name, name)
    if not os.access(p, os.X_OK):
        sys.exit("mm_families.py: %s not found (build the target %s)" % (p, name))
    return p


def ini_value(path, section, key):
    sec = None
    for line in open(path):
        s = line.split("#")[0].strip()
        if s.startswith("["):
            sec = s[1:-1]
        elif sec == section and "=" in s and s.split("=", 1)[0].strip() == key:
            return s.split("=", 1)[1].strip()
    return None


def write_ini(src, keys, dst):
    """src with its @include made absolute and [DynamicKFSLAM] keys (a module's in its own
    section, ini_sections.py) replaced by `keys`."""
    core, modules = split_keys(keys)
    out = []
    for line in open(src):
        s = line.split("#")[0].strip()
        if s.startswith("@include"):
            inc = s.split()[1]
            line = "@include %s\n" % os.path.normpath(os.path.join(os.path.dirname(src), inc))
        k = s.split("=", 1)[0].strip() if "=" in s else None
        if k in keys:
            continue
        out.append(line)
        if s == "[DynamicKFSLAM]":
            out.extend("%s = %s\n" % kv for kv in core.items())
    out.append(modules)
    open(dst, "w").writelines(out)


def nees_rows(path):
    """(key, nees, dof) of each row of an _ego.csv / _object_poses.csv with a finite NEES."""
    rows = []
    if not os.path.exists(path):
        return rows
    for r in csv.DictReader(open(path)):
        if r.get("nees") in (None, "", "nan", "inf"):
            continue
        v = float(r["nees"])
        dof = int(r.get("dof") or 3)
        if math.isfinite(v) and dof > 0:
            rows.append(((int(r.get("object", -1)), int(r["step"])), v, dof))
    return rows


def run_seed(exe, inis, family, seed, out, keep):
    scen, vary_world, level = FAMILIES[family]
    d = os.path.join(out, "work", "%s_%d" % (family, seed))
    os.makedirs(d, exist_ok=True)
    cmd = [exe["sim"], "-c", os.path.join(CONFIG, scen), "-o", d, "--noise-seed", str(seed)]
    if vary_world:
        cmd += ["--world-seed", str(seed)]
    if level:
        cmd += ["--noise", level]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    base = os.path.join(d, ini_value(os.path.join(CONFIG, scen), "Scenario", "name"))
    runs = [("E", "static_landmarks_only,dynamic_cv,dynamic_mm,default", {}),
            ("P", "dynamic", {})]
    if family == "markov":
        runs.append(("M", "dynamic_mm", {"dynamic_mm": "mm_matched"}))
    result, nees = [], {}
    for tag, filters, rename in runs:
        c = os.path.join(d, "cmp" + tag)
        t0 = time.time()
        p = subprocess.run([exe["cmp"], "-q", "--no-figures", "-c", inis[tag], "-r",
                            base + ".rawlog", "--gt", base, "-o", c, "--filters", filters],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if p.returncode != 0:
            result.append({"family": family, "seed": seed, "row": tag, "error":
                           p.stdout.strip().splitlines()[-1] if p.stdout.strip() else "failed"})
            continue
        wall = time.time() - t0
        for r in csv.DictReader(open(os.path.join(c, "metrics.csv"))):
            f = r["filter"]
            row = rename.get(f, ROW_NAMES.get(f, f))
            obj = nees_rows(os.path.join(c, f + "_object_poses.csv"))
            ego = nees_rows(os.path.join(c, f + "_ego.csv"))
            result.append({
                "family": family, "seed": seed, "row": row, "ate": r["ate"],
                "ego_anees": r["ego_anees"], "ate_gap": r.get("ate_gap", ""),
                "ego_nees_gap": r.get("ego_nees_gap", ""),
                "obj_pose_anees": ("%.6g" % (sum(x[1] for x in obj) / sum(x[2] for x in obj))
                                   if obj else ""),
                "ms_per_step": r["ms_per_step"], "wall_s": "%.2f" % wall, "error": ""})
            if family == "markov":
                nees[row] = {"ego": ego, "obj": obj}
    if not keep:
        shutil.rmtree(d, ignore_errors=True)
    return result, nees


def chi2_bounds(k, z=1.959963985):
    """95 % two-sided chi-square quantiles of k dof (Wilson-Hilferty)."""
    return tuple(k * (1 - 2 / (9 * k) + s * z * math.sqrt(2 / (9 * k))) ** 3 for s in (-1, 1))


def mc_consistency(per_seed):
    """per_seed: list (one per seed) of [(key, nees, dof)]. Per key the mean over the seeds
    against the 95 % bounds of chi2(sum dof) / N; returns (ANEES over everything, keys inside,
    keys, mean of the per-key normalised means)."""
    by = {}
    for rows in per_seed:
        for key, v, dof in rows:
            by.setdefault(key, []).append((v, dof))
    inside = 0
    for vals in by.values():
        n, k = len(vals), sum(x[1] for x in vals)
        lo, hi = chi2_bounds(k)
        inside += lo <= sum(x[0] for x in vals) <= hi
    tot = sum(v for rows in per_seed for _, v, _ in rows)
    dof = sum(d for rows in per_seed for _, _, d in rows)
    return (tot / dof if dof else float("nan")), inside, len(by)


def summarize(rows, families):
    ok = [r for r in rows if not r["error"]]
    errors = [r for r in rows if r["error"]]
    by = {}
    for r in ok:
        by.setdefault((r["family"], r["row"]), {})[int(r["seed"])] = r
    lines = ["| family | row | seeds | mean ATE [m] | % seeds <= 1.05 x paper | worst ratio | "
             "median ratio | mean ego ANEES | max ego ANEES |", "|---|---|---|---|---|---|---|---|---|"]
    targets = ["| family | row | <= 1.05 x paper in >= 95 % of seeds | <= 1.2 x paper in every "
               "seed | ego ANEES <= 3 (mean; seeds above 3) | tunnel: <= 0.5 x "
               "static_landmarks_only in every seed |", "|---|---|---|---|---|---|"]
    for fam in families:
        paper = by.get((fam, "paper"), {})
        for row in ROWS + ["static_landmarks_only", "mm_matched"]:
            rs = by.get((fam, row))
            if not rs:
                continue
            seeds = sorted(s for s in rs if s in paper)
            ratios = [float(rs[s]["ate"]) / float(paper[s]["ate"]) for s in seeds]
            an = [float(rs[s]["ego_anees"]) for s in rs if rs[s]["ego_anees"]]
            lines.append("| %s | %s | %d | %.4f | %.0f | %.3f | %.3f | %s | %s |" % (
                fam, row, len(rs), st.mean(float(r["ate"]) for r in rs.values()),
                100.0 * sum(x <= 1.05 for x in ratios) / len(ratios) if ratios else float("nan"),
                max(ratios) if ratios else float("nan"),
                st.median(ratios) if ratios else float("nan"),
                "%.2f" % st.mean(an) if an else "-", "%.2f" % max(an) if an else "-"))
            if row in ("default", "cv", "mm") and ratios:
                frac = sum(x <= 1.05 for x in ratios) / len(ratios)
                worst = max(ratios)
                over3 = sum(x > 3 for x in an)
                tun = ""
                ref = by.get((fam, "static_landmarks_only"), {})
                if fam == "tunnel" and ref:
                    q = [float(rs[s]["ate"]) / float(ref[s]["ate"]) for s in seeds if s in ref]
                    tun = "%s (%d of %d seeds; median %.3f)" % (
                        "met" if all(x <= 0.5 for x in q) else "NOT met",
                        sum(x <= 0.5 for x in q), len(q), st.median(q))
                targets.append("| %s | %s | %s (%.0f %%) | %s (worst %.3f) | %s (%.2f; %d) | %s |"
                               % (fam, row, "met" if frac >= 0.95 else "NOT met", 100 * frac,
                                  "met" if worst <= 1.2 else "NOT met", worst,
                                  "met" if an and st.mean(an) <= 3 and over3 == 0 else "NOT met",
                                  st.mean(an) if an else float("nan"), over3, tun or "-"))
    txt = "\n".join(lines) + "\n\nTargets of issue 28 (for the default profile; cv and mm as candidates):\n\n" + \
        "\n".join(targets) + "\n"
    if errors:
        txt += "\nFailed runs: %d (%s)\n" % (len(errors), "; ".join(
            "%s %s %s: %s" % (e["family"], e["seed"], e["row"], e["error"]) for e in errors[:10]))
    return txt


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--seeds", type=int, default=50)
    ap.add_argument("--seed0", type=int, default=3000)
    ap.add_argument("--level-seeds", type=int, default=None,
                    help="seeds of the highway_<level> families (default: --seeds)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--families", default=",".join(FAMILIES))
    ap.add_argument("--keep", action="store_true", help="keep the per-seed folders")
    ap.add_argument("--table-only", action="store_true", help="summarize OUT/runs.csv only")
    a = ap.parse_args()
    fams = [f for f in a.families.split(",") if f]
    for f in fams:
        if f not in FAMILIES:
            sys.exit("mm_families.py: unknown family '%s' (known: %s)" % (f, ", ".join(FAMILIES)))
    os.makedirs(a.out, exist_ok=True)
    runs_csv = os.path.join(a.out, "runs.csv")
    cols = ["family", "seed", "row", "ate", "ego_anees", "ate_gap", "ego_nees_gap",
            "obj_pose_anees", "ms_per_step", "wall_s", "error"]
    if a.table_only:
        rows = list(csv.DictReader(open(runs_csv)))
    else:
        exe = {"sim": find_exe(a.build, "dynslam-simulate"),
               "cmp": find_exe(a.build, "dynslam-compare")}
        tunnel = os.path.join(CONFIG, "compare_tunnel.ini")
        inis = {"E": os.path.join(a.out, "compare_E.ini"),
                "P": os.path.join(a.out, "compare_P.ini"),
                "M": os.path.join(a.out, "compare_M.ini")}
        write_ini(tunnel, {}, inis["E"])
        write_ini(tunnel, {"prior_gauge": "prior"}, inis["P"])
        write_ini(os.path.join(CONFIG, "compare_tunnel_markov.ini"), {}, inis["M"])
        nlev = a.seeds if a.level_seeds is None else a.level_seeds
        jobs = [(f, s) for f in fams
                for s in range(a.seed0, a.seed0 + (nlev if f.startswith("highway_") else a.seeds))]
        rows, nees = [], {}
        t0 = time.time()
        fh = open(runs_csv, "w", newline="")  # written as the runs finish (a partial campaign
        w = csv.DictWriter(fh, fieldnames=cols, extrasaction="ignore")  # can be summarized)
        w.writeheader()
        with cf.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futs = {pool.submit(run_seed, exe, inis, f, s, a.out, a.keep): (f, s)
                    for f, s in jobs}
            for i, fu in enumerate(cf.as_completed(futs)):
                r, n = fu.result()
                rows += r
                for x in r:
                    w.writerow({c: x.get(c, "") for c in cols})
                fh.flush()
                for row, v in n.items():
                    nees.setdefault(row, []).append(v)
                if (i + 1) % 20 == 0 or i + 1 == len(jobs):
                    print("%d/%d runs, %.0f s" % (i + 1, len(jobs), time.time() - t0),
                          flush=True)
        fh.close()
        rows.sort(key=lambda r: (fams.index(r["family"]), int(r["seed"]), r["row"]))
        with open(runs_csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=cols, extrasaction="ignore")
            w.writeheader()
            for r in rows:
                w.writerow({c: r.get(c, "") for c in cols})
        if nees:
            lines = ["| row | seeds | ego ANEES (all steps) | ego steps whose MC mean is inside "
                     "the 95 % bounds | object-pose ANEES | object (object, step) keys inside |",
                     "|---|---|---|---|---|---|"]
            for row, per in sorted(nees.items()):
                ea, ei, en = mc_consistency([p["ego"] for p in per])
                oa, oi, on = mc_consistency([p["obj"] for p in per])
                lines.append("| %s | %d | %.3f | %d of %d (%.0f %%) | %.3f | %d of %d (%.0f %%) |"
                             % (row, len(per), ea, ei, en, 100.0 * ei / max(en, 1), oa, oi, on,
                                100.0 * oi / max(on, 1)))
            open(os.path.join(a.out, "markov_nees.md"), "w").write("\n".join(lines) + "\n")
            print("\n".join(lines))
    txt = summarize(rows, [f for f in FAMILIES if f in fams])
    open(os.path.join(a.out, "summary.md"), "w").write(txt)
    print(txt)


if __name__ == "__main__":
    main()
