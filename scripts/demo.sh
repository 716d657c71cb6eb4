#!/usr/bin/env bash
# The README's first command: installs what is missing, builds hsmap,
# simulates the small `tiny` survey (with ground truth), inspects it, runs
# the `sequential` variant on it (front-end and geo-referencing) and scores
# the result against the truth with `hsmap evaluate`.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-"$here/build"}
"$here/scripts/setup.sh"
BUILD_DIR="$build_dir" "$here/scripts/build.sh" --target hsmap
hsmap="$build_dir/tools/hsmap"
survey="$build_dir/tiny-survey"
run="$build_dir/tiny-run"
"$hsmap" simulate --preset tiny --out "$survey" --force
"$hsmap" inspect "$survey"
"$hsmap" run "$survey" --out "$run" --variant sequential --force
"$hsmap" evaluate "$run" --truth "$survey/truth"
metric() { sed -nE "s/^ *\"$1\": ([^,]+),?$/\1/p" "$run/metrics.json"; }
echo
echo "The run is in $run: trajectory/frames.csv and uhi_lines.csv (every frame and"
echo "scan line posed in W), map/sparse.ply, calibration.yaml, run.yaml."
echo "Against the truth ($run/metrics.json): frame positions $(metric rgb_ate_m) m RMS"
echo "as placed by the INS (the INS alone allows $(metric ins_floor_rgb_ate_m) m), and"
echo "$(metric rgb_ate_aligned_m) m RMS in shape once aligned."
