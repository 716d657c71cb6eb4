#!/usr/bin/python3
"""Each calibration component of a run against the survey's truth, in units
of the run's stated 1-sigma.

    scripts/calibration_errors.py RUN/calibration.yaml SURVEY/truth/calibration.yaml

Rotation: the rotation vector of R_true^-1 R_est (about U's x, y, z, degrees);
translation: t_est - t_true (along C's x, y, z, millimetres); d: d_est -
d_true (milliseconds). Prints one line per component and the largest
|error| / sigma. A component whose sigma is null (the `sequential` variant's
d, which it keeps at the survey's guess) is printed as not estimated and
left out of the largest ratio.
"""
import sys

import numpy as np
import yaml


def rotation(wxyz):
    w, x, y, z = wxyz
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def rotation_vector(R):
    angle = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))
    axis = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if angle < 1e-12:
        return axis / 2
    return axis / (2 * np.sin(angle)) * angle


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    run = yaml.safe_load(open(sys.argv[1]))
    truth = yaml.safe_load(open(sys.argv[2]))
    for key in ("sigma_rotation_deg", "sigma_translation_m"):
        if key not in run["T_C_U"]:
            sys.exit(f"{sys.argv[1]}: key T_C_U.{key} missing (a joint run states it)")
    if "time_offset_sigma_s" not in run:
        sys.exit(f"{sys.argv[1]}: key time_offset_sigma_s missing (a joint run states it)")
    R_est = rotation(run["T_C_U"]["rotation_wxyz"])
    R_true = rotation(truth["T_C_U"]["rotation_wxyz"])
    rot_err = np.degrees(rotation_vector(R_true.T @ R_est))
    trans_err = (np.array(run["T_C_U"]["translation_m"]) - np.array(truth["T_C_U"]["translation_m"])) * 1000
    d_err = (run["time_offset_s"] - truth["time_offset_s"]) * 1000
    rows = []
    def scaled(sigma, factor):
        return None if sigma is None else sigma * factor

    sigma_rotation = run["T_C_U"]["sigma_rotation_deg"] or [None] * 3
    sigma_translation = run["T_C_U"]["sigma_translation_m"] or [None] * 3
    for axis, e, s in zip("xyz", rot_err, sigma_rotation):
        rows.append((f"rotation about U's {axis}", e, s, "deg"))
    for axis, e, s in zip("xyz", trans_err, sigma_translation):
        rows.append((f"translation along C's {axis}", e, scaled(s, 1000), "mm"))
    rows.append(("time offset d", d_err, scaled(run["time_offset_sigma_s"], 1000), "ms"))
    ratios = []
    for name, e, s, unit in rows:
        if s is None:
            print(f"{name:28s} error {e:9.4f} {unit:3s} (not estimated: no sigma)")
            continue
        print(f"{name:28s} error {e:9.4f} {unit:3s} sigma {s:8.4f} {unit:3s} ({abs(e) / s:.2f} sigma)")
        ratios.append(abs(e) / s)
    if ratios:
        print(f"largest error / sigma: {max(ratios):.2f}")


if __name__ == "__main__":
    main()
