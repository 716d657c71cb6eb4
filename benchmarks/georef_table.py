#!/usr/bin/python3
"""One Markdown table of trajectory metrics from metrics.json files.

    georef_table.py NAME=RUN/metrics.json ...

Rows in the order given; columns: variant, the absolute frame error
(rgb_ate_m) beside the INS floor, the shape (rgb_ate_aligned_m), the scale
error beside the INS floor and the 1-sigma georef states for it
(RUN/georef/map_placement.yaml, sequential; its error in sigmas), and the
scan lines' errors after the frames' alignment. Used by
benchmarks/georef_benchmark.sh.
"""
import json
import os
import re
import sys

from table_cells import cell




def stated_scale_sigma(metrics_path):
    """scale_sigma of georef/map_placement.yaml beside metrics.json, or None."""
    path = os.path.join(os.path.dirname(metrics_path), "georef", "map_placement.yaml")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        match = re.search(r"^scale_sigma:\s*(\S+)", f.read(), re.MULTILINE)
    return float(match.group(1)) if match else None


def in_sigmas(error, sigma):
    if error is None or sigma is None or sigma <= 0:
        return "—"
    return f"{error / sigma:.1f} σ"


print("| survey | variant | rgb_ate_m | INS floor | rgb_ate_aligned_m | rgb_scale_error | INS floor | "
      "stated scale 1-sigma | error in sigmas | uhi_position_rmse_m | uhi_rotation_rmse_deg |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for argument in sys.argv[1:]:
    name, path = argument.split("=", 1)
    with open(path) as f:
        m = json.load(f)
    print(f"| {name} | {m['variant']} | {cell(m['rgb_ate_m'], 100, 1, ' cm')} | "
          f"{cell(m.get('ins_floor_rgb_ate_m'), 100, 1, ' cm')} | "
          f"{cell(m['rgb_ate_aligned_m'], 1000, 1, ' mm')} | "
          f"{cell(m['rgb_scale_error'], 100, 2, ' %')} | "
          f"{cell(m.get('ins_floor_scale_error'), 100, 2, ' %')} | "
          f"{cell(stated_scale_sigma(path), 100, 2, ' %')} | "
          f"{in_sigmas(m.get('rgb_scale_error'), stated_scale_sigma(path))} | "
          f"{cell(m['uhi_position_rmse_m'], 1000, 1, ' mm')} | "
          f"{cell(m['uhi_rotation_rmse_deg'], 1, 2, '°')} |")
