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
# A metric of metrics.json, scaled and rounded (awk: no extra package).
metric() {
  sed -nE "s/^ *\"$1\": ([^,]+),?$/\1/p" "$run/metrics.json" |
    awk -v scale="$2" -v unit="$3" '{ printf "%.1f %s", $1 * scale, unit }'
}
echo
echo "The run is in $run: trajectory/frames.csv and uhi_lines.csv (every frame"
echo "and scan line posed in W), map/sparse.ply, calibration.yaml, run.yaml."
echo "Scores against the truth ($run/metrics.json): every frame's position to"
echo "$(metric rgb_ate_m 100 cm) RMS as placed by the INS (the INS alone allows $(metric ins_floor_rgb_ate_m 100 cm)),"
echo "and the trajectory's shape to $(metric rgb_ate_aligned_m 1000 mm) RMS once aligned."
