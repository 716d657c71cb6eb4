#!/usr/bin/python3
"""One Markdown table of every variant's metrics from metrics.json files.

    variants_table.py NAME=RUN/metrics.json[=WALL=PEAK_MB] ...

Rows in the order given; columns: variant, the extrinsic's rotation and
translation errors, the time offset's error, the ortho-image's registration
RMSE and coverage, the trajectory's shape (rgb_ate_aligned_m), the mesh's
accuracy, and the run's wall time and peak memory when given. A metric the
evaluation left null shows "null". Used by benchmarks/variants_benchmark.sh.
"""
import json
import functools
import sys

import table_cells

# A metric the evaluation left out is null in metrics.json: say so.
cell = functools.partial(table_cells.cell, missing="null")


print("| survey | variant | T_C_U rotation error | translation error | d error | ortho_registration_rmse_m | "
      "ortho_coverage | rgb_ate_aligned_m | mesh_accuracy_m | run wall | peak |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for argument in sys.argv[1:]:
    parts = argument.split("=")
    if len(parts) not in (2, 4):
        sys.exit(f"variants_table.py: expected NAME=METRICS[=WALL=PEAK_MB], got {argument}")
    name, path = parts[0], parts[1]
    with open(path) as f:
        m = json.load(f)
    wall, peak = (parts[2], f"{parts[3]} MB") if len(parts) == 4 else ("", "")
    print(f"| {name} | {m['variant']} | {cell(m['extrinsic_rotation_error_deg'], 1, 3, '°')} | "
          f"{cell(m['extrinsic_translation_error_m'], 1000, 1, ' mm')} | "
          f"{cell(m['time_offset_error_s'], 1000, 2, ' ms')} | "
          f"{cell(m['ortho_registration_rmse_m'], 1000, 1, ' mm')} | "
          f"{cell(m['ortho_coverage'], 1, 3)} | "
          f"{cell(m['rgb_ate_aligned_m'], 1000, 1, ' mm')} | "
          f"{cell(m['mesh_accuracy_m'], 1000, 1, ' mm')} | {wall} | {peak} |")
