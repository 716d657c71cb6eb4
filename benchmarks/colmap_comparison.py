#!/usr/bin/python3
"""hsmap's front-end beside COLMAP on the first frames of a simulated survey.

Usage: benchmarks/colmap_comparison.py SURVEY [FRAMES] [BUILD_DIR]

Both get the same FRAMES (default 300) first RGB frames of SURVEY and the
same, known camera (COLMAP's FULL_OPENCV model with the survey's
pinhole-radtan intrinsics, held fixed):
  - hsmap: `hsmap run SUB --until frontend` on a survey folder SUB that lists
    only those frames (the other files are links to SURVEY's);
  - COLMAP (Debian's `colmap`, CPU only): feature_extractor (SIFT, at most
    SIFT_FEATURES per image), sequential_matcher (each frame against the
    next SEQUENTIAL_OVERLAP and those 2^k ahead), mapper, model_converter.
Each is timed as a whole process (wall clock). The registered frames' camera
centres are aligned to truth/rgb_poses.csv with the same Sim(3) (Umeyama)
and the RMS position error is reported, also as % of the path length of
those frames. Work goes to ${WORK_DIR:-/tmp}/hsmap_colmap_comparison. Prints
a Markdown table. Needs colmap and python3-numpy (Debian packages).
"""
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frontend_accuracy import read_rows, umeyama  # noqa: E402


# COLMAP settings for a video on 2 CPU cores: SIFT features per image and
# the number of following frames each frame is matched with, plus frames
# 2^k ahead (quadratic overlap: without those wide-baseline pairs the mapper
# finds no initial pair on a slow survey). COLMAP's defaults (8192 features,
# overlap 10) take about an hour here.
SIFT_FEATURES = 2000
SEQUENTIAL_OVERLAP = 5


def quaternion_to_matrix(w, x, y, z):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def aligned_rms(estimated, true):
    estimated, true = np.array(estimated), np.array(true)
    scale, rotation, translation = umeyama(estimated, true)
    aligned = (scale * (rotation @ estimated.T)).T + translation
    return float(np.sqrt(((aligned - true) ** 2).sum(axis=1).mean()))


def run(command, log):
    start = time.monotonic()
    with open(log, "a") as out:
        subprocess.run(command, check=True, stdout=out, stderr=subprocess.STDOUT)
    return time.monotonic() - start


def camera_params(survey):
    text = open(os.path.join(survey, "survey.yaml")).read()
    rgb = text[text.index("rgb:"):text.index("uhi:")]
    value = lambda key: float(re.search(rf"\b{key}: ([-0-9.e+]+)", rgb).group(1))
    distortion = [float(v) for v in re.search(r"distortion: \[([^\]]*)\]", rgb).group(1).split(",")]
    k1, k2, p1, p2, k3 = distortion
    return [value("fx"), value("fy"), value("cx"), value("cy"), k1, k2, p1, p2, k3, 0, 0, 0]


def main():
    if not 2 <= len(sys.argv) <= 4:
        sys.exit(__doc__)
    survey = os.path.abspath(sys.argv[1])
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 300
    build = sys.argv[3] if len(sys.argv) > 3 else "build"
    hsmap = os.path.abspath(os.path.join(build, "tools", "hsmap"))
    work = os.path.join(os.environ.get("WORK_DIR", "/tmp"), "hsmap_colmap_comparison")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    log = os.path.join(work, "log.txt")

    frames = read_rows(os.path.join(survey, "rgb", "frames.csv"))[:count]
    truth = read_rows(os.path.join(survey, "truth", "rgb_poses.csv"))[:count]
    true_centres = {f["file"]: [float(t[k]) for k in "xyz"] for f, t in zip(frames, truth)}
    path = float(np.linalg.norm(np.diff(np.array(list(true_centres.values())), axis=0), axis=1).sum())

    # The sub-survey for hsmap and the image folder for COLMAP: links, no copies.
    sub = os.path.join(work, "survey")
    images = os.path.join(work, "images")
    os.makedirs(os.path.join(sub, "rgb"))
    os.makedirs(images)
    for entry in os.listdir(survey):
        if entry not in ("rgb", "truth"):
            os.symlink(os.path.join(survey, entry), os.path.join(sub, entry))
    with open(os.path.join(sub, "rgb", "frames.csv"), "w") as out:
        out.write("file,t\n")
        for f in frames:
            out.write(f"{f['file']},{f['t']}\n")
            source = os.path.join(survey, "rgb", f["file"])
            os.symlink(source, os.path.join(sub, "rgb", f["file"]))
            os.symlink(source, os.path.join(images, f["file"]))

    rows = []
    hsmap_run = os.path.join(work, "run")
    seconds = run([hsmap, "run", sub, "--out", hsmap_run, "--until", "frontend"], log)
    posed = read_rows(os.path.join(hsmap_run, "frontend", "frames.csv"))
    estimated, true = [], []
    for f, row in zip(frames, posed):
        if row["posed"] == "1":
            estimated.append([float(row[k]) for k in "xyz"])
            true.append(true_centres[f["file"]])
    rms = aligned_rms(estimated, true)
    rows.append(("hsmap front-end", seconds, len(estimated), rms))

    database = os.path.join(work, "colmap.db")
    sparse = os.path.join(work, "sparse")
    text_model = os.path.join(work, "text")
    os.makedirs(sparse)
    os.makedirs(text_model)
    params = ",".join(repr(v) for v in camera_params(survey))
    start = time.monotonic()
    run(["colmap", "feature_extractor", "--database_path", database, "--image_path", images,
         "--ImageReader.camera_model", "FULL_OPENCV", "--ImageReader.single_camera", "1",
         "--ImageReader.camera_params", params, "--SiftExtraction.use_gpu", "0",
         "--SiftExtraction.max_num_features", str(SIFT_FEATURES)], log)
    run(["colmap", "sequential_matcher", "--database_path", database,
         "--SiftMatching.use_gpu", "0", "--SequentialMatching.overlap", str(SEQUENTIAL_OVERLAP),
         "--SequentialMatching.quadratic_overlap", "1"], log)
    try:
        run(["colmap", "mapper", "--database_path", database, "--image_path", images,
             "--output_path", sparse, "--Mapper.ba_refine_focal_length", "0",
             "--Mapper.ba_refine_principal_point", "0", "--Mapper.ba_refine_extra_params", "0"],
            log)
    except subprocess.CalledProcessError:
        pass  # no model ("failed to create sparse model"): reported as 0 frames registered
    seconds = time.monotonic() - start
    models = sorted(os.listdir(sparse))
    best = None
    for model in models:  # COLMAP may split the sequence into several models: take the largest
        out = os.path.join(text_model, model)
        os.makedirs(out)
        run(["colmap", "model_converter", "--input_path", os.path.join(sparse, model),
             "--output_path", out, "--output_type", "TXT"], log)
        centres = {}
        lines = [l for l in open(os.path.join(out, "images.txt")) if not l.startswith("#")]
        for line in lines[0::2]:
            fields = line.split()
            qw, qx, qy, qz, tx, ty, tz = map(float, fields[1:8])
            rotation = quaternion_to_matrix(qw, qx, qy, qz)  # R_C_W
            centres[fields[9]] = -rotation.T @ np.array([tx, ty, tz])
        if best is None or len(centres) > len(best):
            best = centres
    names = [f["file"] for f in frames if best and f["file"] in best]
    rms = aligned_rms([best[n] for n in names], [true_centres[n] for n in names]) if len(names) >= 3 else float("nan")
    rows.append((f"COLMAP 3.8 (largest of {len(models)} model(s))", seconds, len(names), rms))

    print(f"{count} frames of {os.path.basename(survey)}, path {path:.2f} m, {os.cpu_count()} cores")
    print("| method | wall time | frames registered | aligned RMS | % of path |")
    print("|---|---:|---:|---:|---:|")
    for name, seconds, registered, rms in rows:
        error = (f"{1000 * rms:.1f} mm | {100 * rms / path:.3f} %" if rms == rms
                 else "- | -")  # nan: nothing registered
        print(f"| {name} | {seconds:.1f} s | {registered} of {count} | {error} |")


if __name__ == "__main__":
    main()
