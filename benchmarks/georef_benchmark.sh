#!/usr/bin/env bash
# Geo-referencing on simulated surveys: for each SURVEY runs
#   hsmap run SURVEY --variant sequential --until georef   (front-end + georef)
#   hsmap run SURVEY --variant sequential --from georef --until georef --force
#                                                   (georef alone, under /usr/bin/time -v)
#   hsmap run SURVEY --variant planar --until georef
#   hsmap evaluate RUN --truth SURVEY/truth         (both runs)
# and prints a Markdown table of every trajectory metric per survey and
# variant, beside the floor the INS allows (metrics.json's ins_floor_*), and
# a second table with the georef stage's wall time and peak memory.
#
#   benchmarks/georef_benchmark.sh SURVEY... [-- BUILD_DIR]
#
# Run folders go to ${WORK_DIR:-/tmp}/hsmap_georef_<name>_<variant>.
# Figures are recorded in docs/BENCHMARKS.md.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=benchmarks/survey_arguments.sh
source "$here/survey_arguments.sh"
runs=()
timing_rows=()
for survey in "${surveys[@]}"; do
  name=$(basename "$survey")
  for variant in sequential planar; do
    run="$work/hsmap_georef_${name}_${variant}"
    rm -rf "$run"
    "$hsmap" run "$survey" --out "$run" --variant "$variant" --until georef >"$run.log" 2>&1
    if [[ $variant == sequential ]]; then
      /usr/bin/time -v "$hsmap" run "$survey" --out "$run" --from georef --until georef --force \
        >"$run.georef.log" 2>"$run.georef.time"
      wall=$(grep "Elapsed (wall clock)" "$run.georef.time" | awk '{print $NF}')
      rss_kb=$(grep "Maximum resident set size" "$run.georef.time" | awk '{print $NF}')
      stage=$(grep -E "^  georef " "$run.georef.log" | awk '{print $2}')
      timing_rows+=("| $name | $stage s | $wall | $((rss_kb / 1024)) MB |")
    fi
    "$hsmap" evaluate "$run" --truth "$survey/truth" >"$run.evaluate.log"
    runs+=("$name=$run/metrics.json")
  done
done
/usr/bin/python3 "$here/georef_table.py" "${runs[@]}"
echo
echo "| survey | georef stage (run.yaml) | whole process (--from georef: load, read frontend/, georef, write) | peak memory |"
echo "|---|---:|---:|---:|"
printf '%s\n' "${timing_rows[@]}"
