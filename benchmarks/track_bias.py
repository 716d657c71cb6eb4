#!/usr/bin/python3
"""Systematic error of the front-end's feature tracks against the true scene.

Usage: benchmarks/track_bias.py RUN SURVEY

For every landmark of RUN/frontend/frame_observations.csv, its first
observation is cast from the TRUE camera pose (SURVEY/truth/rgb_poses.csv)
onto the TRUE seabed (SURVEY/truth/scene.ply), and the point found is
projected into every later frame that tracked it, through the survey's
pinhole-radtan camera. The difference tracked - predicted, along the
direction the point moved in the image since its first observation, is the
tracker's error along the motion. A tracker without systematic error scores
0 on average; a negative ratio means the tracks fall short of the motion
(by that fraction of the distance travelled in the image). Such a shortfall,
the same sign for every track, is what the bundle adjustments turn into a
scale that drifts along the track (docs/BENCHMARKS.md, "Geo-referencing").

Prints the observations used, the mean along-motion error over displacement
(least squares through the origin) overall, per displacement range, per
starting image row (quarters of the height) and per fifth of the survey.

The truth's scene must be a height field on a regular grid (the simulator's
`flat`, `low-relief` and `transect-100m`; `rugged` adds rock meshes and is
refused). Frames are matched by index: frame i of frames.csv is row i of
rgb/frames.csv and of the truth.
"""
import csv
import sys

import numpy as np
import yaml


def fail(message):
    sys.exit("track_bias.py: " + message)


def read_ply_vertices(path):
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                fail(f"{path}: no end_header")
            header += line
        lines = header.decode("ascii").split("\n")
        if "format binary_little_endian 1.0" not in lines:
            fail(f"{path}: expected a binary little-endian PLY")
        vertex = [l for l in lines if l.startswith("element vertex")]
        props = []
        in_vertex = False
        for l in lines:
            if l.startswith("element"):
                in_vertex = l.startswith("element vertex")
            elif in_vertex and l.startswith("property"):
                props.append(l.split())
        if [p[1:] for p in props[:3]] != [["double", "x"], ["double", "y"], ["double", "z"]] or len(props) != 3:
            fail(f"{path}: expected vertices of exactly double x, y, z")
        count = int(vertex[0].split()[2])
        return np.frombuffer(f.read(count * 24), dtype="<f8").reshape(-1, 3)


class HeightField:
    def __init__(self, vertices, path):
        xs, ys = np.unique(vertices[:, 0]), np.unique(vertices[:, 1])
        if len(xs) * len(ys) != len(vertices):
            fail(f"{path}: the scene is not a height field on a regular grid "
                 f"({len(vertices)} vertices, {len(xs)} x {len(ys)} distinct x, y)")
        self.x0, self.y0 = xs[0], ys[0]
        self.dx, self.dy = (xs[-1] - xs[0]) / (len(xs) - 1), (ys[-1] - ys[0]) / (len(ys) - 1)
        ix = np.rint((vertices[:, 0] - self.x0) / self.dx).astype(int)
        iy = np.rint((vertices[:, 1] - self.y0) / self.dy).astype(int)
        self.z = np.full((len(ys), len(xs)), np.nan)
        self.z[iy, ix] = vertices[:, 2]

    def __call__(self, x, y):
        gx, gy = (x - self.x0) / self.dx, (y - self.y0) / self.dy
        c = np.clip(np.floor(gx).astype(int), 0, self.z.shape[1] - 2)
        r = np.clip(np.floor(gy).astype(int), 0, self.z.shape[0] - 2)
        fx, fy = gx - c, gy - r
        z = self.z
        return (z[r, c] * (1 - fx) * (1 - fy) + z[r, c + 1] * fx * (1 - fy) + z[r + 1, c] * (1 - fx) * fy +
                z[r + 1, c + 1] * fx * fy)


class Camera:
    def __init__(self, config, path):
        if config.get("model") != "pinhole-radtan":
            fail(f"{path}: rgb.camera.model: expected pinhole-radtan")
        self.fx, self.fy, self.cx, self.cy = (float(config[k]) for k in ("fx", "fy", "cx", "cy"))
        d = [float(v) for v in config.get("distortion", [0, 0, 0, 0, 0])] + [0.0] * 5
        self.k1, self.k2, self.p1, self.p2, self.k3 = d[:5]

    def distort(self, x, y):
        r2 = x * x + y * y
        radial = 1 + self.k1 * r2 + self.k2 * r2 * r2 + self.k3 * r2 * r2 * r2
        return (x * radial + 2 * self.p1 * x * y + self.p2 * (r2 + 2 * x * x),
                y * radial + self.p1 * (r2 + 2 * y * y) + 2 * self.p2 * x * y)

    def project(self, p_C):
        x, y = self.distort(p_C[:, 0] / p_C[:, 2], p_C[:, 1] / p_C[:, 2])
        return self.fx * x + self.cx, self.fy * y + self.cy

    def ray(self, u, v):
        xd, yd = (u - self.cx) / self.fx, (v - self.cy) / self.fy
        x, y = xd.copy(), yd.copy()
        for _ in range(30):  # fixed point: x = xd - (distort(x) - x)
            dx, dy = self.distort(x, y)
            x, y = x - (dx - xd), y - (dy - yd)
        return np.stack([x, y, np.ones_like(x)], axis=-1)


def rotation_matrices(q):
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)


def ratio(along, moved):
    return (along * moved).sum() / (moved * moved).sum()


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    run, survey = sys.argv[1], sys.argv[2]
    with open(f"{survey}/survey.yaml") as f:
        camera = Camera(yaml.safe_load(f)["rgb"]["camera"], f"{survey}/survey.yaml")
    scene = HeightField(read_ply_vertices(f"{survey}/truth/scene.ply"), f"{survey}/truth/scene.ply")
    truth = np.loadtxt(f"{survey}/truth/rgb_poses.csv", delimiter=",", skiprows=1, ndmin=2)
    R_W_C, c_W = rotation_matrices(truth[:, 4:8]), truth[:, 1:4]
    obs = np.loadtxt(f"{run}/frontend/frame_observations.csv", delimiter=",", skiprows=1, ndmin=2)
    frame, landmark, u, v = obs[:, 0].astype(int), obs[:, 1].astype(int), obs[:, 2], obs[:, 3]
    if frame.max() >= len(truth):
        fail(f"frame {frame.max()} observed, the truth has {len(truth)} poses")
    order = np.lexsort((frame, landmark))
    frame, landmark, u, v = frame[order], landmark[order], u[order], v[order]
    first = np.r_[True, landmark[1:] != landmark[:-1]]
    track = np.cumsum(first) - 1
    f0, u0, v0 = frame[first], u[first], v[first]

    # First observation's ray, from the true pose, onto the true height field.
    d_W = np.einsum("nij,nj->ni", R_W_C[f0], camera.ray(u0, v0))
    origin = c_W[f0]
    depth = np.full(len(f0), np.nanmean(scene.z))
    t = (depth - origin[:, 2]) / d_W[:, 2]
    for _ in range(30):
        p = origin + t[:, None] * d_W
        t = (scene(p[:, 0], p[:, 1]) - origin[:, 2]) / d_W[:, 2]
    X_W = origin + t[:, None] * d_W

    p_C = np.einsum("nji,nj->ni", R_W_C[frame], X_W[track] - c_W[frame])
    u_pred, v_pred = camera.project(p_C)
    du, dv = u - u_pred, v - v_pred
    mu, mv = u - u0[track], v - v0[track]
    moved = np.hypot(mu, mv)
    use = (moved > 20) & np.isfinite(du) & np.isfinite(dv)
    along = (du * mu + dv * mv) / np.maximum(moved, 1e-9)
    a, m = along[use], moved[use]
    print(f"observations {len(u)}, tracks {first.sum()}, used {use.sum()} (moved more than 20 px)")
    print(f"along-motion error / distance moved: {ratio(a, m):+.2e}")
    for lo, hi in ((20, 100), (100, 200), (200, 300), (300, 450), (450, 10000)):
        s = (m >= lo) & (m < hi)
        if s.any():
            print(f"  moved {lo}-{hi} px: {s.sum()} observations, mean error {a[s].mean():+.4f} px, "
                  f"ratio {ratio(a[s], m[s]):+.2e}")
    height = 2 * camera.cy
    start_v = v0[track][use]
    for q in range(4):
        s = (start_v >= q * height / 4) & (start_v < (q + 1) * height / 4)
        if s.any():
            print(f"  first seen in rows {q * height / 4:.0f}-{(q + 1) * height / 4:.0f}: "
                  f"{s.sum()} observations, ratio {ratio(a[s], m[s]):+.2e}")
    start_f = f0[track][use]
    for q in range(5):
        s = (start_f >= q * len(truth) / 5) & (start_f < (q + 1) * len(truth) / 5)
        if s.any():
            print(f"  fifth {q + 1} of the survey: ratio {ratio(a[s], m[s]):+.2e}")


if __name__ == "__main__":
    main()
