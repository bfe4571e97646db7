#!/usr/bin/env python3
"""Cuts the excerpt shipped in datasets/mrclam/MRCLAM_Dataset6_excerpt from a full MRCLAM
Dataset 6 folder (development only; the build and the tests never run this).

  python3 make_excerpt.py /path/to/MRCLAM_Dataset6 MRCLAM_Dataset6_excerpt

Window [T0, T0 + SPAN] (absolute Vicon/robot time). Every file keeps its 4 header lines.
- Barcodes.dat, Landmark_Groundtruth.dat: copied.
- RobotR_Measurement.dat, RobotR_Odometry.dat (R = ROBOT = 3): measurement: every row in the window, unchanged.
- odometry: rows in the window, minus rows whose (v, w) repeat the previous row's
  (lossless under the importer's zero-order hold: the integral is unchanged).
- RobotN_Groundtruth.dat (N = 1..5): every GT_STEP-th row in the window (about 6-8 Hz)."""
import os
import sys

T0 = 1248444180.0
SPAN = 130.0
GT_STEP = 10
ROBOT = 3


def split(path):
    with open(path) as f:
        lines = f.readlines()
    head = [l for l in lines if l.startswith('#')]
    body = [l for l in lines if not l.startswith('#') and l.strip()]
    return head, body


def inside(line):
    t = float(line.split()[0])
    return T0 <= t <= T0 + SPAN


def write(path, head, body):
    with open(path, 'w') as f:
        f.writelines(head + body)


def main(src, dst):
    os.makedirs(dst, exist_ok=True)
    for name in ('Barcodes.dat', 'Landmark_Groundtruth.dat'):
        write(os.path.join(dst, name), *split(os.path.join(src, name)))
    head, body = split(os.path.join(src, 'Robot%d_Measurement.dat' % ROBOT))
    write(os.path.join(dst, 'Robot%d_Measurement.dat' % ROBOT), head, [l for l in body if inside(l)])
    head, body = split(os.path.join(src, 'Robot%d_Odometry.dat' % ROBOT))
    out, prev = [], None
    for l in body:
        if not inside(l):
            continue
        cmd = tuple(float(x) for x in l.split()[1:])
        if cmd != prev:
            out.append(l)
        prev = cmd
    write(os.path.join(dst, 'Robot%d_Odometry.dat' % ROBOT), head, out)
    for r in range(1, 6):
        head, body = split(os.path.join(src, 'Robot%d_Groundtruth.dat' % r))
        rows = [l for l in body if inside(l)]
        write(os.path.join(dst, 'Robot%d_Groundtruth.dat' % r), head, rows[::GT_STEP])


if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2])
