#!/usr/bin/python3
"""One Markdown table of the surface stage from benchmarks/surface_benchmark.sh.

    surface_table.py NAME|SURFACE|RUN|PEAK_RSS_KB ...

Reads RUN/run.yaml (the surface stage's time), RUN/metrics.json and the
vertex and face counts of RUN/map/mesh.ply's header.
"""
import json
import re
import sys


def ply_counts(path):
    counts = {}
    with open(path, "rb") as f:
        for raw in f:
            line = raw.decode("ascii", "replace").strip()
            match = re.match(r"element (vertex|face) (\d+)", line)
            if match:
                counts[match.group(1)] = int(match.group(2))
            if line == "end_header":
                break
    return counts.get("vertex", 0), counts.get("face", 0)


def stage_time(run_yaml, stage):
    text = open(run_yaml).read()
    match = re.search(r"\{name: " + stage + r", time_s: ([0-9.eE+-]+)", text)
    return float(match.group(1)) if match else None


def mm(value):
    return "n/a" if value is None else f"{value * 1000:.1f} mm"


def fraction(value):
    return "n/a" if value is None else f"{value:.3f}"


print("| survey | surface | vertices | triangles | surface stage | peak memory | mesh_accuracy_m | "
      "mesh_completeness | attitude-aligned accuracy | attitude-aligned completeness |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for argument in sys.argv[1:]:
    name, surface, run, rss_kb = argument.split("|")
    with open(f"{run}/metrics.json") as f:
        m = json.load(f)
    vertices, faces = ply_counts(f"{run}/map/mesh.ply")
    seconds = stage_time(f"{run}/run.yaml", "surface")
    print(f"| {name} | {surface} | {vertices:,} | {faces:,} | "
          f"{'n/a' if seconds is None else f'{seconds:.1f} s'} | {int(rss_kb) / 1024 / 1024:.2f} GB | "
          f"{mm(m.get('mesh_accuracy_m'))} | {fraction(m.get('mesh_completeness'))} | "
          f"{mm(m.get('mesh_accuracy_attitude_aligned_m'))} | "
          f"{fraction(m.get('mesh_completeness_attitude_aligned'))} |")
