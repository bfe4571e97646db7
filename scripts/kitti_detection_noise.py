#!/usr/bin/env python3
"""Measures the noise of a 3-D detector's boxes against the KITTI tracking labels, as the
filters see them: the range and bearing residuals of the four footprint corners in the ego
frame (doc/boxes.md "Noise of the detector's corners"). Plain Python (no numpy).

  scripts/kitti_detection_noise.py LABEL_DIR DET_DIR [SEQ ...] [--class Car] [--min-score S]

LABEL_DIR: KITTI label_02 (SSSS.txt); DET_DIR: the PointRCNN folder (CLASS/SSSS.txt). A
detection is paired with the label box of its type nearest to it in the bird's-eye view (centre
within 2 m; each label box at most once per frame, nearest pairs first); the front/back
ambiguity is resolved per pair (the orientation with the smaller corner error). Prints per
sequence: pairs, rms range and bearing residual of the corners, the mean centre and yaw error,
the detections left unpaired (false positives within 40 m and 45 deg) and the label boxes left
unpaired (misses, same region)."""
import math
import sys


def ego_box(x, z, ry, l, w):
    """camera (x, z, rot_y) -> ego (forward, left, yaw), as the importer does."""
    return (z, -x, -ry - math.pi / 2, l, w)


def corners(b):
    cx, cy, yaw, l, w = b
    c, s = math.cos(yaw), math.sin(yaw)
    out = []
    for lx, ly in ((l / 2, w / 2), (l / 2, -w / 2), (-l / 2, -w / 2), (-l / 2, w / 2)):
        out.append((cx + c * lx - s * ly, cy + s * lx + c * ly))
    return out


def in_region(b, max_range=40.0, half_fov=math.radians(45)):
    return math.hypot(b[0], b[1]) <= max_range and abs(math.atan2(b[1], b[0])) <= half_fov


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def read_labels(path, types):
    frames = {}
    for line in open(path):
        t = line.split()
        if len(t) < 17 or t[2] not in types:
            continue
        h, w, l, x, y, z, ry = map(float, t[10:17])
        frames.setdefault(int(t[0]), []).append(ego_box(x, z, ry, l, w))
    return frames


def read_dets(path, min_score):
    frames = {}
    for line in open(path):
        t = line.strip().split(",")
        if len(t) != 15:
            continue
        score = float(t[6])
        if score < min_score:
            continue
        h, w, l, x, y, z, ry = map(float, t[7:14])
        frames.setdefault(int(t[0]), []).append(ego_box(x, z, ry, l, w) + (score,))
    return frames


def main():
    args = [a for a in sys.argv[1:]]
    cls, min_score = "Car", -1e9
    if "--class" in args:
        i = args.index("--class")
        cls = args[i + 1]
        del args[i:i + 2]
    if "--min-score" in args:
        i = args.index("--min-score")
        min_score = float(args[i + 1])
        del args[i:i + 2]
    label_dir, det_dir = args[0], args[1]
    seqs = args[2:] or ["%04d" % k for k in range(11)]
    print("seq,pairs,rms_range,rms_bearing_rad,mean_centre_err,rms_yaw_err_modpi,fp_in_region,"
          "fn_in_region,label_boxes_in_region")
    tot = [0, 0.0, 0.0]
    for s in seqs:
        labels = read_labels("%s/%s.txt" % (label_dir, s), {cls})
        dets = read_dets("%s/%s/%s.txt" % (det_dir, cls, s), min_score)
        n = 0
        sr = sb = sc = sy = 0.0
        fp = fn = gtn = 0
        for f in sorted(set(labels) | set(dets)):
            L = [b for b in labels.get(f, []) if in_region(b)]
            D = dets.get(f, [])
            gtn += len(L)
            pairs = sorted((math.hypot(d[0] - g[0], d[1] - g[1]), i, j)
                           for i, d in enumerate(D) for j, g in enumerate(L))
            ud, ug = set(), set()
            for dist, i, j in pairs:
                if dist > 2.0 or i in ud or j in ug:
                    continue
                ud.add(i)
                ug.add(j)
                d, g = D[i], L[j]
                best = None
                for flip in (0.0, math.pi):
                    dc = corners((d[0], d[1], d[2] + flip, d[3], d[4]))
                    gc = corners(g)
                    err = sum((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 for a, b in zip(dc, gc))
                    if best is None or err < best[0]:
                        best = (err, dc, gc, flip)
                _, dc, gc, flip = best
                for a, b in zip(dc, gc):
                    sr += (math.hypot(*a) - math.hypot(*b)) ** 2
                    sb += wrap(math.atan2(a[1], a[0]) - math.atan2(b[1], b[0])) ** 2
                n += 1
                sc += dist
                sy += wrap(d[2] + flip - g[2]) ** 2
            fp += sum(1 for i, d in enumerate(D) if i not in ud and in_region(d))
            fn += len(L) - len(ug)
        if n:
            print("%s,%d,%.4f,%.5f,%.4f,%.4f,%d,%d,%d" % (
                s, n, math.sqrt(sr / (4 * n)), math.sqrt(sb / (4 * n)), sc / n,
                math.sqrt(sy / n), fp, fn, gtn))
            tot[0] += n
            tot[1] += sr
            tot[2] += sb
    if tot[0]:
        print("all,%d,%.4f,%.5f,,,,," % (tot[0], math.sqrt(tot[1] / (4 * tot[0])),
                                         math.sqrt(tot[2] / (4 * tot[0]))))


if __name__ == "__main__":
    main()
