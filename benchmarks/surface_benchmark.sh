#!/usr/bin/env bash
# The surface stage on simulated surveys, dense beside sparse: for each SURVEY
#   hsmap run SURVEY --variant sequential --until georef     (front-end + georef, once)
#   hsmap run SURVEY --from georef --force --surface dense   (under /usr/bin/time -v)
#   hsmap run SURVEY --from georef --force --surface sparse  (into a copy of the run)
#   hsmap evaluate RUN --truth SURVEY/truth                  (both)
# and prints one Markdown table: points, triangles, the surface stage's time
# (run.yaml), the whole process's peak memory (time -v; the georef stage that
# reruns with it is ~0.25 GB of it on the 20 m presets), mesh_accuracy_m and
# mesh_completeness, and the same under the attitude-anchored alignment
# (metrics.json's *_attitude_aligned keys, docs/EVALUATE.md).
#
#   benchmarks/surface_benchmark.sh SURVEY... [-- BUILD_DIR]
#
# Run folders go to ${WORK_DIR:-/tmp}/hsmap_surface_<name>_{dense,sparse}.
# Figures are recorded in docs/BENCHMARKS.md ("Surface").
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=benchmarks/survey_arguments.sh
source "$here/survey_arguments.sh"
rows=()
for survey in "${surveys[@]}"; do
  name=$(basename "$survey")
  dense="$work/hsmap_surface_${name}_dense"
  rm -rf "$dense" "$work/hsmap_surface_${name}_sparse"
  "$hsmap" run "$survey" --out "$dense" --until georef >"$dense.georef.log" 2>&1
  cp -r "$dense" "$work/hsmap_surface_${name}_sparse"
  for surface in dense sparse; do
    run="$work/hsmap_surface_${name}_${surface}"
    /usr/bin/time -v "$hsmap" run "$survey" --out "$run" --from georef --force --surface "$surface" \
      >"$run.log" 2>"$run.time"
    "$hsmap" evaluate "$run" --truth "$survey/truth" >"$run.evaluate.log"
    rows+=("$name|$surface|$run|$(grep "Maximum resident set size" "$run.time" | awk '{print $NF}')")
  done
done
/usr/bin/python3 "$here/surface_table.py" "${rows[@]}"
