#!/usr/bin/env bash
# Times `hsmap simulate` on a preset with /usr/bin/time -v (wall time, CPU
# time, peak memory) and prints the simulator's own per-stage summary.
#
#   benchmarks/simulate_benchmark.sh [PRESET] [WORK_DIR] [BUILD_DIR]
#
# Defaults: PRESET=rugged, WORK_DIR=/tmp, BUILD_DIR=build. The survey is
# written to WORK_DIR/hsmap_simulate_benchmark_PRESET and removed at the end
# unless KEEP=1. Figures are recorded in docs/BENCHMARKS.md.
set -euo pipefail
preset="${1:-rugged}"
work="${2:-/tmp}"
build="${3:-build}"
hsmap="$build/tools/hsmap"
[[ -x "$hsmap" ]] || { echo "error: $hsmap not found; build it with scripts/build.sh --target hsmap" >&2; exit 1; }
out="$work/hsmap_simulate_benchmark_$preset"
log="$work/hsmap_simulate_benchmark_$preset.log"
rm -rf "$out"
echo "simulating preset $preset into $out on $(nproc) cores"
/usr/bin/time -v "$hsmap" simulate --preset "$preset" --out "$out" >"$log" 2>"$log.time"
sed -n '/^simulated survey written/,$p' "$log"
grep -E "Elapsed \(wall clock\)|User time|System time|Maximum resident set size" "$log.time" | sed 's/^\s*/  /'
du -sh "$out" | awk '{print "  survey size: " $1}'
if [[ "${KEEP:-0}" != 1 ]]; then rm -rf "$out"; fi
