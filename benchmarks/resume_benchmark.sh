#!/usr/bin/env bash
# Resuming and restarting `hsmap run` on a survey (docs/RUN.md):
#   1. a full run (--threads 1, so that every sum runs in one order);
#   2. the same command again on the finished run, timed: every stage is
#      skipped as up to date;
#   3. for each stage X of the variant, `--from X` on the finished run, its
#      products compared byte for byte (md5sum) with the full run's.
# Prints one Markdown table per variant. Usage:
#   benchmarks/resume_benchmark.sh SURVEY [VARIANT ...] -- BUILD_DIR
# e.g. benchmarks/resume_benchmark.sh /work/surveys/rugged sequential joint -- build
# WORK_DIR (default /tmp) holds the runs; STAGES (e.g. "joint products")
# restricts step 3 to those stages (a joint run's earlier stages take most of
# an hour on rugged).
set -euo pipefail
survey=$1
shift
variants=()
while [[ $# -gt 0 && $1 != "--" ]]; do variants+=("$1"); shift; done
[[ ${#variants[@]} -eq 0 ]] && variants=(sequential)
[[ $# -ge 2 && $1 == "--" ]] || { echo "usage: $0 SURVEY [VARIANT ...] -- BUILD_DIR" >&2; exit 2; }
hsmap="$2/tools/hsmap"
work=${WORK_DIR:-/tmp}
name=$(basename "$survey")

products() {  # the contract's files and the products, with their md5
  # (stacked has no trajectory/, map/ or calibration.yaml: find's complaint is not a failure)
  (cd "$1" && { find trajectory map hyperspectral calibration.yaml -type f 2>/dev/null || true; } | sort | xargs md5sum)
}

for variant in "${variants[@]}"; do
  run="$work/hsmap_resume_${name}_$variant"
  rm -rf "$run"
  case $variant in
    sequential) stages=(frontend georef surface refine products) ;;
    joint) stages=(frontend georef surface joint products) ;;
    planar) stages=(georef surface products) ;;
    stacked) stages=(products) ;;
    *) echo "unknown variant $variant" >&2; exit 2 ;;
  esac
  all_stages=${#stages[@]}
  if [[ -n ${STAGES:-} ]]; then read -r -a stages <<<"$STAGES"; fi
  start=$(date +%s.%N)
  "$hsmap" run "$survey" --out "$run" --variant "$variant" --threads 1 >"$run.full.log" 2>&1
  full_s=$(echo "$(date +%s.%N) - $start" | bc)
  products "$run" >"$run.full.md5"
  start=$(date +%s.%N)
  "$hsmap" run "$survey" --out "$run" --variant "$variant" --threads 1 >"$run.again.log" 2>&1
  again_s=$(echo "$(date +%s.%N) - $start" | bc)
  skipped=$(grep -c ": up to date, skipped" "$run.again.log" || true)
  echo "### $name, $variant"
  if [[ -n ${STAGES:-} ]]; then echo "<!-- STAGES=$STAGES -->"; fi
  echo
  echo "| command | wall (s) | result |"
  echo "|---|---:|---|"
  printf '| `hsmap run %s --out RUN --variant %s --threads 1` | %.1f | %d files |\n' "$name" "$variant" "$full_s" "$(wc -l <"$run.full.md5")"
  printf '| the same again | %.2f | %d of %d stages up to date, skipped |\n' "$again_s" "$skipped" "$all_stages"
  for stage in "${stages[@]}"; do
    start=$(date +%s.%N)
    "$hsmap" run "$survey" --out "$run" --variant "$variant" --threads 1 --from "$stage" >"$run.from_$stage.log" 2>&1
    from_s=$(echo "$(date +%s.%N) - $start" | bc)
    products "$run" >"$run.from_$stage.md5"
    differing=$(diff "$run.full.md5" "$run.from_$stage.md5" | grep -c '^>' || true)
    if [[ $differing -eq 0 ]]; then result="products byte-identical to the full run's"; else result="$differing files differ"; fi
    printf '| `--from %s` | %.1f | %s |\n' "$stage" "$from_s" "$result"
  done
  echo
done
