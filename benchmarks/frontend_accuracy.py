#!/usr/bin/python3
"""Aligned position error of the front-end's frame poses against the truth.

Usage: benchmarks/frontend_accuracy.py RUN SURVEY

Reads RUN/frontend/frames.csv (T_F_C of every posed frame, up to scale) and
SURVEY/truth/rgb_poses.csv (T_W_C of every frame), fits the best similarity
(Umeyama: rotation, translation, scale) of the posed frames' positions onto
the true ones, and prints one line of key=value pairs: frames, posed, the
truth's path length, the aligned RMS position error (m) and that error as a
percentage of the path length. The frames are matched by row: frame i of
frames.csv is row i of rgb/frames.csv and of the truth (same time stamps,
checked).
"""
import csv
import sys

import numpy as np


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def umeyama(source, target):
    """Similarity (s, R, t) minimising |target - (s R source + t)|^2."""
    mu_s, mu_t = source.mean(axis=0), target.mean(axis=0)
    xs, xt = source - mu_s, target - mu_t
    cov = xt.T @ xs / len(source)
    u, d, vt = np.linalg.svd(cov)
    sign = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        sign[2, 2] = -1.0
    rotation = u @ sign @ vt
    variance = (xs ** 2).sum() / len(source)
    scale = np.trace(np.diag(d) @ sign) / variance
    translation = mu_t - scale * rotation @ mu_s
    return scale, rotation, translation


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    run, survey = sys.argv[1], sys.argv[2]
    frames = read_rows(f"{run}/frontend/frames.csv")
    truth = read_rows(f"{survey}/truth/rgb_poses.csv")
    if len(frames) != len(truth):
        sys.exit(f"{run}/frontend/frames.csv has {len(frames)} rows, the truth {len(truth)}")
    posed, true = [], []
    for row, true_row in zip(frames, truth):
        if abs(float(row["t"]) - float(true_row["t"])) > 1e-6:
            sys.exit(f"frame {row['frame']}: time {row['t']} differs from the truth's {true_row['t']}")
        if row["posed"] == "1":
            posed.append([float(row[k]) for k in "xyz"])
            true.append([float(true_row[k]) for k in "xyz"])
    all_true = np.array([[float(r[k]) for k in "xyz"] for r in truth])
    path = float(np.linalg.norm(np.diff(all_true, axis=0), axis=1).sum())
    posed, true = np.array(posed), np.array(true)
    scale, rotation, translation = umeyama(posed, true)
    aligned = (scale * (rotation @ posed.T)).T + translation
    rms = float(np.sqrt(((aligned - true) ** 2).sum(axis=1).mean()))
    print(f"frames={len(frames)} posed={len(posed)} path_m={path:.3f} "
          f"aligned_rms_m={rms:.4f} percent_of_path={100 * rms / path:.3f}")


if __name__ == "__main__":
    main()
