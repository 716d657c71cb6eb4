#!/usr/bin/env bash
# Fuzzes the survey input parsers (tests/fuzz, docs/FUZZING.md): installs
# clang if missing (scripts/setup.sh --fuzz), builds the libFuzzer targets
# with ASan + UBSan in build-fuzz/ (RelWithDebInfo, HSMAP_FUZZ=ON) and runs
# each target for SECONDS (default 600).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#   targets: envi_header_fuzz csv_tables_fuzz strict_yaml_fuzz (default: all)
#
# Per target, in build-fuzz/fuzz-runs/<target>/:
#   corpus/    the working corpus, seeded from tests/fuzz/corpus/<target>; it
#              keeps what libFuzzer adds, so a later run starts further on
#   findings/  the inputs of findings (crash-*, leak-*, timeout-*, oom-*);
#              copy them to tests/fuzz/regressions/<target>/ (docs/FUZZING.md)
#   last.log   libFuzzer's output of the last run (stacks of findings)
# The regression inputs (tests/fuzz/regressions/) are not fed to the fuzzer:
# CTest replays them, and one still failing would stop every run at its start.
# At the end a table gives per target: executions, exec/s, coverage
# (libFuzzer's cov: and ft: at the end of the run), corpus size and findings
# of this run. Exit status 1 when a target found something, 2 for bad
# arguments.
#
# Environment: BUILD_DIR (default build-fuzz/), FUZZ_JOBS (build jobs, default
# nproc), FUZZ_ARGS (more libFuzzer options, e.g. "-max_len=16384").
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-"$here/build-fuzz"}
all_targets=(envi_header_fuzz csv_tables_fuzz strict_yaml_fuzz)

usage() {
  echo "usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: ${all_targets[*]})" >&2
  exit 2
}
seconds=600
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then
  seconds=$1
  shift
fi
((seconds > 0)) || usage
targets=("$@")
((${#targets[@]} > 0)) || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $t "* ]] || usage
done

"$here/scripts/setup.sh" --fuzz
compiler=$(command -v clang++ || command -v clang++-14 || true)
if [[ -z $compiler ]]; then
  echo "fuzz: clang++ not found; run scripts/setup.sh --fuzz" >&2
  exit 1
fi
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if ! grep -qs "^HSMAP_FUZZ:BOOL=ON" "$build_dir/CMakeCache.txt"; then
  cmake -S "$here" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER="$compiler" -DHSMAP_FUZZ=ON -DHSMAP_BUILD_TESTS=ON \
    -DHSMAP_BUILD_BENCHMARKS=OFF
fi
cmake --build "$build_dir" --parallel "${FUZZ_JOBS:-$(nproc)}" --target "${targets[@]}"

# Symbolised stacks in reports: ASan looks for `llvm-symbolizer` on PATH.
if ! command -v llvm-symbolizer >/dev/null 2>&1 && [[ -z ${ASAN_SYMBOLIZER_PATH:-} ]]; then
  for candidate in llvm-symbolizer-14 llvm-symbolizer-15 llvm-symbolizer-16; do
    if command -v "$candidate" >/dev/null 2>&1; then
      export ASAN_SYMBOLIZER_PATH=$(command -v "$candidate")
      break
    fi
  done
fi
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

# The value of `stat::NAME:` in a libFuzzer log (-print_final_stats=1), or '-'.
final_stat() {
  local value
  value=$(grep -E "^stat::$1:" "$2" | tail -n 1 | awk '{print $2}')
  echo "${value:--}"
}

rows=()
found_any=0
for t in "${targets[@]}"; do
  run_dir="$build_dir/fuzz-runs/$t"
  seeds="$here/tests/fuzz/corpus/$t"
  mkdir -p "$run_dir/corpus" "$run_dir/findings"
  # Seed the working corpus (never overwrite: it may hold better inputs).
  for seed in "$seeds"/*; do
    if [[ -f $seed && ! -e "$run_dir/corpus/$(basename "$seed")" ]]; then
      cp "$seed" "$run_dir/corpus/"
    fi
  done
  options=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
           -artifact_prefix="$run_dir/findings/")
  dict="$here/tests/fuzz/dictionaries/$t.dict"
  if [[ -f $dict ]]; then options+=(-dict="$dict"); fi
  read -r -a extra <<<"${FUZZ_ARGS:-}"

  log="$run_dir/last.log"
  marker="$run_dir/.run-start"
  touch "$marker"
  echo "fuzz: $t for ${seconds} s (log: $log)"
  status=0
  "$build_dir/tests/fuzz/$t" "${options[@]}" "${extra[@]}" "$run_dir/corpus" >"$log" 2>&1 || status=$?

  findings=$(find "$run_dir/findings" -type f -newer "$marker" | wc -l)
  if ((findings > 0)); then
    found_any=1
    echo "fuzz: $t: $findings finding(s) in $run_dir/findings/; the report:"
    grep -naE "^==[0-9]+== ?ERROR|runtime error|uncaught exception|not one line|SUMMARY|Test unit written" \
      "$log" | head -n 20 || true
  elif ((status != 0)); then
    found_any=1
    findings="error"
    echo "fuzz: $t: libFuzzer exited with status $status and saved no input; the end of $log:"
    tail -n 20 "$log"
  fi
  coverage=$(grep -oE "cov: [0-9]+ ft: [0-9]+ corp: [0-9]+" "$log" | tail -n 1 || true)
  cov=$(awk '{print $2}' <<<"$coverage")
  ft=$(awk '{print $4}' <<<"$coverage")
  corp=$(awk '{print $6}' <<<"$coverage")
  rows+=("$(printf '%-18s %12s %8s %6s %7s %7s %9s' "$t" "$(final_stat number_of_executed_units "$log")" \
    "$(final_stat average_exec_per_sec "$log")" "${cov:--}" "${ft:--}" "${corp:--}" "$findings")")
done

echo
printf '%-18s %12s %8s %6s %7s %7s %9s\n' target executions exec/s cov ft corpus findings
for row in "${rows[@]}"; do echo "$row"; done
exit "$found_any"
