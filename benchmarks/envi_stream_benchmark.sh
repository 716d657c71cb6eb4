#!/usr/bin/env bash
# envi_stream_benchmark.sh [DIR [BUILD_DIR]]
#
# Streaming read of a ~2 GB ENVI cube (1920 samples x 211 bands x 2650 lines,
# uint16, the UHI's shape) per interleave (bil, bip, bsq), compared with
# `cat FILE > /dev/null` on the same, page-cached file.
#
# For each interleave: writes the cube into DIR (default /tmp) with
# envi_stream_tool, warms the page cache with one `cat`, then runs `cat` and
# the reader (both EnviReader modes: buffered = pread, the default; mapped =
# mmap) 3 times each under /usr/bin/time -v, and deletes the cube. Prints one
# table row per interleave and mode: median wall time of cat, median wall
# time of the reader, their ratio, and the reader's peak RSS (max of the runs).
# The per-run lines also give CPU time (user + sys), which varies less than
# wall time when other work shares the machine.
#
# The tool is found as $HSMAP_ENVI_STREAM_TOOL, else BUILD_DIR (argument 2 or
# $HSMAP_BUILD_DIR)/benchmarks/envi_stream_tool, else <repo>/build/benchmarks/.
# This script builds nothing. ENVI_BENCH_LINES overrides the line count.
# Needs about 2.2 GB free in DIR (one cube at a time).
set -euo pipefail

dir=${1:-/tmp}
build_dir=${2:-${HSMAP_BUILD_DIR:-}}
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tool=${HSMAP_ENVI_STREAM_TOOL:-}
if [[ -z "$tool" ]]; then
  for candidate in ${build_dir:+"$build_dir/benchmarks/envi_stream_tool"} "$repo/build/benchmarks/envi_stream_tool"; do
    if [[ -x "$candidate" ]]; then tool=$candidate; break; fi
  done
fi
if [[ -z "$tool" || ! -x "$tool" ]]; then
  echo "envi_stream_tool not found: build it (ninja envi_stream_tool) and pass the build dir" >&2
  exit 2
fi
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time (GNU time) is required" >&2; exit 2; }

lines=${ENVI_BENCH_LINES:-2650}
runs=3
log=$(mktemp)
current=""
cleanup() {
  rm -f "$log"
  if [[ -n "$current" ]]; then rm -f "$current.hdr" "$current.raw" "$current.raw.partial"; fi
}
trap cleanup EXIT

# Seconds from GNU time's "Elapsed (wall clock) time (h:mm:ss or m:ss): 0:01.23".
elapsed() { awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s}' "$1"; }
cpu_seconds() { awk -F': ' '/User time \(seconds\)|System time \(seconds\)/ {s += $2} END {print s}' "$1"; }
max_rss_kb() { awk -F': ' '/Maximum resident set size/ {print $2}' "$1"; }
median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), kernel $(uname -r)"
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "tool: $tool"
rows=()
for interleave in bil bip bsq; do
  current="$dir/envi_stream_bench_$interleave"
  "$tool" write "$current.hdr" --samples 1920 --bands 211 --lines "$lines" --interleave "$interleave" --type 12
  cat "$current.raw" > /dev/null  # warm the page cache
  cat_times=()
  cat_cpu=()
  for ((r = 0; r < runs; r++)); do
    /usr/bin/time -v cat "$current.raw" > /dev/null 2> "$log"
    cat_times+=("$(elapsed "$log")")
    cat_cpu+=("$(cpu_seconds "$log")")
  done
  cat_median=$(printf '%s\n' "${cat_times[@]}" | median)
  for mode in buffered mapped; do
    reader_times=()
    reader_cpu=()
    peak_kb=0
    for ((r = 0; r < runs; r++)); do
      /usr/bin/time -v "$tool" read "$current.hdr" --mode "$mode" > /dev/null 2> "$log"
      reader_times+=("$(elapsed "$log")")
      reader_cpu+=("$(cpu_seconds "$log")")
      rss=$(max_rss_kb "$log")
      if ((rss > peak_kb)); then peak_kb=$rss; fi
    done
    reader_median=$(printf '%s\n' "${reader_times[@]}" | median)
    rows+=("$(awk -v il="$interleave" -v m="$mode" -v c="$cat_median" -v r="$reader_median" -v k="$peak_kb" \
      'BEGIN {printf "| %-10s | %-8s | %12.2f | %15.2f | %5.2f | %19.0f |", il, m, c, r, (c > 0 ? r / c : 0), k / 1024}')")
    echo "$interleave $mode: wall cat ${cat_times[*]} s, reader ${reader_times[*]} s;" \
      "CPU (user+sys) cat ${cat_cpu[*]} s, reader ${reader_cpu[*]} s; peak RSS $((peak_kb / 1024)) MB"
  done
  rm -f "$current.hdr" "$current.raw"
  current=""
done
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| interleave | mode     | cat median s | reader median s | ratio | reader peak RSS MB |"
echo "|------------|----------|--------------|-----------------|-------|--------------------|"
printf '%s\n' "${rows[@]}"
