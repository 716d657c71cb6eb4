#!/usr/bin/env bash
# The products stage (ray casting of every UHI scan line + the hyperspectral
# ortho-image) against the time to read the cube once: for each SURVEY
#   hsmap run SURVEY --out RUN --until refine ARGS      (once, if the refine stage has not finished)
#   cat SURVEY/uhi/cube.raw > /dev/null                 (timed, from storage: the read floor, in this run)
#   hsmap run SURVEY --out RUN --from products ARGS     (under /usr/bin/time -v)
# and prints one Markdown table: scan lines, the products stage's time
# (run.yaml), the ray casting plus ortho-image alone (from the stage's log:
# reading the mesh and building its BVH, the footprint cast and the ortho
# tiles, i.e. cast, read, accumulate, fill and write ENVI; without the
# quick-look, the RGB ortho-image, the point cloud and the GeoTIFF), scan lines per second of each, the ratio of
# the stage's time to cat's, the process's peak memory (time -v), the
# ortho-image's size on disk and the disk's write speed in the same repeat
# (the cube, in the page cache after the cat, copied with dd oflag=direct to
# a file beside the run and deleted; the ortho-image is written the same
# way, so its size over this speed is the stage's floor on this disk), that
# floor over the cat's time (the lowest stage / cat the disk allows) and the
# stage's time over the floor (1: the stage runs at the disk's write speed).
# The stage's own report (HyperspectralReport::summary, with the time of
# each step) is in RUN.products.log.
#
#   benchmarks/hyperspectral_benchmark.sh SURVEY... [-- BUILD_DIR]
#
# Run folders go to ${WORK_DIR:-/tmp}/hsmap_products_<name> (an existing one
# with a finished surface is reused). Set REPEATS=n to time the stage n times
# (each with its own cat); the table then has one row per repeat.
# PRODUCTS_ARGS adds options to the timed run, e.g. "--no-geotiff" to time
# the casting and ENVI ortho-image apart from the GeoTIFF export.
# "Reading the cube once" means from storage, as a survey just copied off
# the vehicle is read: the cube is dropped from the page cache first
# (dd iflag=nocache count=0, posix_fadvise DONTNEED on the file; no root
# needed), then cat reads it. The stage runs right after, so it sees the
# page cache the cat left: a cube smaller than the free memory is read from
# memory, and the stage's time is its cast, ortho-image and writes.
# Set CUBE_CACHE=keep to skip the drop (the cat then times a memory copy
# whenever the cube is already cached).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=benchmarks/survey_arguments.sh
source "$here/survey_arguments.sh"
repeats="${REPEATS:-1}"
read -r -a products_args <<<"${PRODUCTS_ARGS:-}"

seconds_now() { date +%s.%N; }

echo "| survey | repeat | scan lines | products stage (s) | lines/s | mesh + cast + ortho (s) | lines/s | cat cube.raw (s) | stage / cat | peak RSS (MB) | ortho.raw (GB) | disk write (GB/s) | ortho.raw at that speed (s) | that / cat | stage / that |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for survey in "${surveys[@]}"; do
  name=$(basename "$survey")
  run="$work/hsmap_products_$name"
  if [[ ! -f "$run/stages/refine.yaml" ]]; then
    # The stages before products, with the same options (the refine stage's
    # --extrinsic-rounds among PRODUCTS_ARGS), so that --from products finds
    # them up to date.
    "$hsmap" run "$survey" --out "$run" --until refine "${products_args[@]}" >"$run.surface.log" 2>&1
  fi
  for ((repeat = 1; repeat <= repeats; ++repeat)); do
    # The previous repeat's products go first, untimed: the run would delete
    # them inside the run, and freeing a 15 GB ortho-image (on a file system
    # mounted with `discard`, trimming its blocks) slows the writes that
    # follow for seconds. A user's run writes into a fresh folder.
    rm -rf "$run/hyperspectral"
    sync
    if [[ "${CUBE_CACHE:-drop}" != keep ]]; then
      dd if="$survey/uhi/cube.raw" iflag=nocache count=0 status=none
    fi
    start=$(seconds_now)
    cat "$survey/uhi/cube.raw" >/dev/null
    cat_s=$(awk -v a="$start" -v b="$(seconds_now)" 'BEGIN { print b - a }')
    start=$(seconds_now)
    dd if="$survey/uhi/cube.raw" of="$run.write_speed" bs=32M oflag=direct status=none
    cube_bytes=$(stat -c %s "$survey/uhi/cube.raw")
    write_gb_s=$(awk -v a="$start" -v b="$(seconds_now)" -v n="$cube_bytes" 'BEGIN { print n / 1e9 / (b - a) }')
    rm -f "$run.write_speed"
    sync
    /usr/bin/time -v "$hsmap" run "$survey" --out "$run" --from products "${products_args[@]}" \
      >"$run.products.log" 2>"$run.products.time"
    # The stage's time from the run record, else the whole process's.
    stage_s=$(grep -oE "\{name: products, time_s: [0-9.eE+-]+" "$run/run.yaml" | awk '{print $NF}' || true)
    if [[ -z "$stage_s" ]]; then
      stage_s=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0;
                 for (i = 1; i <= n; ++i) s = s * 60 + t[i]; print s}' "$run.products.time")
    fi
    lines=$(grep -ohE "scan lines: [0-9]+ cast" "$run.products.log" "$run.products.time" 2>/dev/null |
            head -1 | grep -oE "[0-9]+" || true)
    # "products: mesh read and its BVH built in M s" and "time: footprint cast
    # A s; ortho tiles B s; ..." in the stage's log.
    mesh_s=$(grep -oE "mesh read and its BVH built in [0-9.eE+-]+ s" "$run.products.log" |
             head -1 | awk '{print $(NF - 1)}' || true)
    cast_ortho_s=$(grep -oE "footprint cast [0-9.eE+-]+ s; ortho tiles [0-9.eE+-]+ s" "$run.products.log" |
                   head -1 | awk -v mesh="${mesh_s:-0}" '{print mesh + $3 + $7}' || true)
    peak_kb=$(grep "Maximum resident set size" "$run.products.time" | awk '{print $NF}')
    ortho_bytes=$(stat -c %s "$run/hyperspectral/ortho.raw" 2>/dev/null || echo 0)
    awk -v survey="$name" -v repeat="$repeat" -v lines="${lines:-0}" -v stage="$stage_s" -v cast_ortho="${cast_ortho_s:-0}" -v cat_s="$cat_s" \
        -v peak="$peak_kb" -v bytes="$ortho_bytes" -v write_gb_s="$write_gb_s" 'BEGIN {
      floor_s = (write_gb_s > 0 ? bytes / 1e9 / write_gb_s : 0)
      printf "| %s | %d | %d | %.1f | %.0f | %.1f | %.0f | %.1f | %.2f | %.0f | %.2f | %.2f | %.1f | %.2f | %.2f |\n", survey, repeat,
             lines, stage, (stage > 0 ? lines / stage : 0), cast_ortho, (cast_ortho > 0 ? lines / cast_ortho : 0),
             cat_s, (cat_s > 0 ? stage / cat_s : 0), peak / 1024, bytes / 1e9, write_gb_s, floor_s,
             (cat_s > 0 ? floor_s / cat_s : 0), (floor_s > 0 ? stage / floor_s : 0) }'
  done
done
