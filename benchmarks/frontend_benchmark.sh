#!/usr/bin/env bash
# The front-end on simulated surveys: runs `hsmap run SURVEY --until frontend`
# under /usr/bin/time -v and prints one Markdown table row per survey:
# frames posed, keyframes, landmarks, the frame positions' RMS error after a
# Sim(3) alignment to the truth (and as % of the path length), losses, speed
# with PNG decoding, speed of tracking alone (decoded frames), wall time and
# peak memory (the whole process).
#
#   benchmarks/frontend_benchmark.sh SURVEY... [-- BUILD_DIR]
#
# Each SURVEY is a folder written by `hsmap simulate` (it needs truth/). Run
# folders go to ${WORK_DIR:-/tmp}/hsmap_frontend_benchmark_<name>. Figures are
# recorded in docs/BENCHMARKS.md. Needs Debian's python3-numpy (scripts/setup.sh --docs).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=benchmarks/survey_arguments.sh
source "$here/survey_arguments.sh"
steps=()
echo "| survey | frames posed | keyframes | landmarks | aligned RMS | % of path | losses | frames/s (with decoding) | frames/s (tracking alone) | wall time | peak memory |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for survey in "${surveys[@]}"; do
  name=$(basename "$survey")
  run="$work/hsmap_frontend_benchmark_$name"
  rm -rf "$run"
  /usr/bin/time -v "$hsmap" run "$survey" --out "$run" --until frontend >"$run.log" 2>"$run.time"
  summary=$(grep -m1 "^front-end: " "$run.log")
  accuracy=$(/usr/bin/python3 "$here/frontend_accuracy.py" "$run" "$survey")
  value() { sed -E "s/.*$1=([^ ]+).*/\1/" <<<"$accuracy"; }
  posed=$(sed -E 's/^front-end: ([0-9]+) of ([0-9]+) frames posed.*/\1 of \2/' <<<"$summary")
  keyframes=$(sed -E 's/.* ([0-9]+) keyframes,.*/\1/' <<<"$summary")
  landmarks=$(sed -E 's/.* ([0-9]+) landmarks,.*/\1/' <<<"$summary")
  losses=$(sed -E 's/.* ([0-9]+) tracking loss(es)?;.*/\1/' <<<"$summary")
  fps=$(sed -E 's/.*; ([0-9.]+) frames\/s \(tracking alone ([0-9.]+)\).*/\1/' <<<"$summary")
  tracking=$(sed -E 's/.*; ([0-9.]+) frames\/s \(tracking alone ([0-9.]+)\).*/\2/' <<<"$summary")
  wall=$(grep "Elapsed (wall clock)" "$run.time" | awk '{print $NF}')
  rss_kb=$(grep "Maximum resident set size" "$run.time" | awk '{print $NF}')
  rms_mm=$(awk -v m="$(value aligned_rms_m)" 'BEGIN { printf "%.1f", m * 1000 }')
  printf '| %s | %s | %s | %s | %s mm | %s %% | %s | %s | %s | %s | %d MB |\n' \
    "$name" "$posed" "$keyframes" "$landmarks" "$rms_mm" \
    "$(value percent_of_path)" "$losses" "$fps" "$tracking" "$wall" "$((rss_kb / 1024))"
  steps+=("$name: $(grep -m1 "time per frame (ms)" "$run.log" | sed 's/^ *//')")
done
echo
echo "Time per frame and step (decode and preprocess run on the prefetch thread):"
for line in "${steps[@]}"; do echo "  $line"; done
