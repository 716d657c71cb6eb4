#!/usr/bin/env bash
# geotiff_export_benchmark.sh [DIR [BUILD_DIR]]
#
# exportEnviToCog (the hyperspectral ortho's GeoTIFF) on a ~2 GB ortho-image
# the size of a survey's (600 samples x 4000 lines x 211 bands, float32 BIL,
# smooth spectra, NaN outside a wandering swath), compared with GDAL's own
# `gdal_translate -of COG` on the same file with the creation options
# exportEnviToCog passed to GDAL's COG driver before it wrote the GeoTIFF
# itself (DEFLATE, floating-point predictor, 512 tiles, AVERAGE overviews, all
# CPUs), and with `cat FILE > /dev/null` (reading the data once).
#
# Writes the ortho into DIR (default /tmp) with geotiff_export_tool, warms the
# page cache, then runs each command RUNS times (default 3) under
# /usr/bin/time -v. Prints per-run wall time, CPU time (user + sys: it varies
# less than wall time when other work shares the machine), peak RSS and output
# size, then a table of medians (RSS: the largest of the runs).
#
# The tool is found as $HSMAP_GEOTIFF_EXPORT_TOOL, else BUILD_DIR (argument 2
# or $HSMAP_BUILD_DIR)/benchmarks/geotiff_export_tool, else
# <repo>/build/benchmarks/. This script builds nothing. GEOTIFF_BENCH_LINES
# overrides the line count, RUNS the number of runs, GEOTIFF_BENCH_SKIP_COG=1
# skips the (slow) gdal_translate reference. Needs about 5 GB free in DIR.
set -euo pipefail

dir=${1:-/tmp}
build_dir=${2:-${HSMAP_BUILD_DIR:-}}
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tool=${HSMAP_GEOTIFF_EXPORT_TOOL:-}
if [[ -z "$tool" ]]; then
  for candidate in ${build_dir:+"$build_dir/benchmarks/geotiff_export_tool"} "$repo/build/benchmarks/geotiff_export_tool"; do
    if [[ -x "$candidate" ]]; then tool=$candidate; break; fi
  done
fi
if [[ -z "$tool" || ! -x "$tool" ]]; then
  echo "geotiff_export_tool not found: build it (make geotiff_export_tool) and pass the build dir" >&2
  exit 2
fi
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time (GNU time) is required" >&2; exit 2; }
command -v gdal_translate > /dev/null || { echo "gdal_translate not found: run scripts/setup.sh" >&2; exit 2; }

lines=${GEOTIFF_BENCH_LINES:-4000}
runs=${RUNS:-3}
work="$dir/geotiff_export_bench"
log=$(mktemp)
cleanup() { rm -rf "$log" "$work"; }
trap cleanup EXIT
rm -rf "$work"
mkdir -p "$work"

# Seconds from GNU time's "Elapsed (wall clock) time (h:mm:ss or m:ss): 0:01.23".
elapsed() { awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s}' "$1"; }
cpu_seconds() { awk -F': ' '/User time \(seconds\)|System time \(seconds\)/ {s += $2} END {print s}' "$1"; }
max_rss_kb() { awk -F': ' '/Maximum resident set size/ {print $2}' "$1"; }
median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(awk '/MemTotal/ {printf "%.0f GB", $2 / 1048576}' /proc/meminfo) RAM, kernel $(uname -r)"
echo "GDAL: $(gdal_translate --version)"
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "tool: $tool"
"$tool" write "$work/ortho.hdr" --lines "$lines"
cat "$work/ortho.raw" > /dev/null  # warm the page cache

export GDAL_PAM_ENABLED=NO  # no .aux.xml beside the outputs
rows=()
# measure NAME OUTPUT COMMAND...: RUNS runs, one table row. OUTPUT is the
# file the command writes inside $work (removed before each run), or "-".
measure() {
  local name=$1 output=$2
  shift 2
  local times=() cpus=() peak_kb=0 size=0
  for ((r = 0; r < runs; r++)); do
    if [[ "$output" == "$work"/* ]]; then rm -f "$output"; fi
    /usr/bin/time -v "$@" > /dev/null 2> "$log"
    times+=("$(elapsed "$log")")
    cpus+=("$(cpu_seconds "$log")")
    local rss
    rss=$(max_rss_kb "$log")
    if ((rss > peak_kb)); then peak_kb=$rss; fi
    if [[ "$output" == "$work"/* ]]; then size=$(stat -c %s "$output"); fi
    echo "$name run $((r + 1)): wall ${times[-1]} s, CPU ${cpus[-1]} s, peak RSS $((rss / 1024)) MB, output $((size / 1048576)) MB"
  done
  if [[ "$output" == "$work"/* ]]; then rm -f "$output"; fi
  local wall cpu
  wall=$(printf '%s\n' "${times[@]}" | median)
  cpu=$(printf '%s\n' "${cpus[@]}" | median)
  rows+=("$(awk -v n="$name" -v w="$wall" -v c="$cpu" -v k="$peak_kb" -v s="$size" \
    'BEGIN {printf "| %-34s | %13.1f | %12.1f | %11.0f | %9.0f |", n, w, c, k / 1024, s / 1048576}')")
}

measure "cat (read once)" - cat "$work/ortho.raw"
measure "exportEnviToCog" "$work/ortho.tif" "$tool" export "$work/ortho.hdr" "$work/ortho.tif"
if [[ "${GEOTIFF_BENCH_SKIP_COG:-0}" != 1 ]]; then
  measure "gdal_translate -of COG (reference)" "$work/cog.tif" gdal_translate -q -of COG \
    -co COMPRESS=DEFLATE -co PREDICTOR=YES -co BLOCKSIZE=512 -co OVERVIEWS=AUTO -co RESAMPLING=AVERAGE \
    -co NUM_THREADS=ALL_CPUS -co BIGTIFF=IF_SAFER "$work/ortho.raw" "$work/cog.tif"
fi
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| command                            | median wall s | median CPU s | peak RSS MB | output MB |"
echo "|------------------------------------|---------------|--------------|-------------|-----------|"
printf '%s\n' "${rows[@]}"
