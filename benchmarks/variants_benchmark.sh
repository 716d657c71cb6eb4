#!/usr/bin/env bash
# Every estimation variant side by side: for each SURVEY runs
#   hsmap run SURVEY --out RUN --variant V --no-geotiff   (V: stacked, planar, sequential, joint)
#   hsmap evaluate RUN --truth SURVEY/truth
# under /usr/bin/time -v and prints one Markdown table (benchmarks/variants_table.py)
# of the calibration, ortho-image, trajectory and mesh metrics per survey
# and variant, with each run's wall time and peak memory.
#
#   benchmarks/variants_benchmark.sh SURVEY... [-- BUILD_DIR]
#
# VARIANTS="sequential joint" runs a subset; RUN_ARGS adds options to every
# run (e.g. "--no-points"). Run folders go to
# ${WORK_DIR:-/tmp}/hsmap_variants_<name>_<variant> (replaced).
# Figures are recorded in docs/BENCHMARKS.md, section "Joint".
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=benchmarks/survey_arguments.sh
source "$here/survey_arguments.sh"
read -r -a variants <<<"${VARIANTS:-stacked planar sequential joint}"
read -r -a run_args <<<"${RUN_ARGS:-}"
rows=()
for survey in "${surveys[@]}"; do
  name=$(basename "$survey")
  for variant in "${variants[@]}"; do
    run="$work/hsmap_variants_${name}_${variant}"
    rm -rf "$run"
    /usr/bin/time -v "$hsmap" run "$survey" --out "$run" --variant "$variant" --no-geotiff "${run_args[@]}" \
      >"$run.log" 2>"$run.time"
    "$hsmap" evaluate "$run" --truth "$survey/truth" >"$run.evaluate.log"
    wall=$(grep "Elapsed (wall clock)" "$run.time" | awk '{print $NF}')
    rss_kb=$(grep "Maximum resident set size" "$run.time" | awk '{print $NF}')
    rows+=("$name=$run/metrics.json=$wall=$((rss_kb / 1024))")
  done
done
/usr/bin/python3 "$here/variants_table.py" "${rows[@]}"
