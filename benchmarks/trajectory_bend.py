#!/usr/bin/python3
"""Where a trajectory's shape error lies: along the track, across it, in depth.

Usage: benchmarks/trajectory_bend.py FRAMES_CSV TRUTH_CSV

FRAMES_CSV: RUN/trajectory/frames.csv (t, x, y, z, ...) or
RUN/frontend/frames.csv (frames with posed = 0 are left out); TRUTH_CSV:
SURVEY/truth/rgb_poses.csv. Frames are matched by time stamp. The positions
are aligned on the truth by the best similarity (Umeyama), as the contract's
shape metric `rgb_ate_aligned_m` is, and the remaining error is split along
the track (the horizontal direction from the first true position to the
last), across it (horizontal) and in depth. For each part it prints the RMS,
the RMS of its best quadratic in the distance travelled (a scale that
drifts along the track bends the along-track error into a parabola) and what
is left, and the error at 0, 25, 50, 75 and 100 % of the track (mm).
"""
import csv
import sys

import numpy as np

from frontend_accuracy import umeyama


def read_positions(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or not {"t", "x", "y", "z"} <= set(rows[0]):
        sys.exit(f"trajectory_bend.py: {path}: expected a CSV with columns t, x, y, z")
    return {round(float(r["t"]), 4): [float(r[c]) for c in "xyz"] for r in rows if r.get("posed", "1") == "1"}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    estimate, truth = read_positions(sys.argv[1]), read_positions(sys.argv[2])
    times = sorted(set(estimate) & set(truth))
    if len(times) < 3:
        sys.exit(f"trajectory_bend.py: {len(times)} frames in common between the two files (time stamps)")
    P = np.array([estimate[t] for t in times])
    Q = np.array([truth[t] for t in times])
    s, R, t = umeyama(P, Q)
    error = (s * (R @ P.T)).T + t - Q
    print(f"frames {len(times)}, similarity scale {s:.6f}, aligned RMS {1000 * np.sqrt((error ** 2).sum(1).mean()):.2f} mm")
    along = Q[-1] - Q[0]
    along[2] = 0.0
    along /= np.linalg.norm(along)
    down = np.array([0.0, 0.0, 1.0])
    distance = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(Q, axis=0), axis=1))]
    for name, axis in (("along", along), ("across", np.cross(down, along)), ("depth", down)):
        e = error @ axis
        fit = np.polyval(np.polyfit(distance, e, 2), distance)
        at = " ".join(f"{1000 * e[int(f * (len(e) - 1))]:+.1f}" for f in (0, 0.25, 0.5, 0.75, 1))
        print(f"{name:6s} RMS {1000 * np.sqrt((e ** 2).mean()):6.2f} mm, quadratic {1000 * np.sqrt((fit ** 2).mean()):6.2f} mm, "
              f"rest {1000 * np.sqrt(((e - fit) ** 2).mean()):6.2f} mm; at 0/25/50/75/100 %: {at}")


if __name__ == "__main__":
    main()
