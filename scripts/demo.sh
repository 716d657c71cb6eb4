#!/usr/bin/env bash
# The README's first command: installs what is missing, builds hsmap,
# simulates the small `tiny` survey (with ground truth), inspects it, runs
# the `sequential` variant on it (front-end, geo-referencing, surface,
# hyperspectral products) and scores
# the result against the truth with `hsmap evaluate`, and ends by printing
# where the run's report is (one page to open in a browser).
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
    awk -v scale="$2" -v unit="$3" '{ if ($1 == "null") printf "(not measured)"; else printf "%.1f %s", $1 * scale, unit }'
}
echo
echo "The run is in $run:"
echo "  hyperspectral/ortho.hdr + ortho.raw  the hyperspectral ortho-image (ENVI, UTM, every band)"
echo "  hyperspectral/ortho.tif              the same as a Cloud-Optimized GeoTIFF (QGIS, gdalinfo)"
echo "  hyperspectral/ortho_rgb.png          its quick-look; map/rgb_ortho.png the RGB ortho-image of the mesh"
echo "  map/mesh.ply                         the dense surface with RGB vertex colours (MeshLab, CloudCompare)"
echo "  trajectory/frames.csv, uhi_lines.csv every frame and scan line posed in W; calibration.yaml, run.yaml"
echo "Scores against the truth ($run/metrics.json): every frame's position to"
echo "$(metric rgb_ate_m 100 cm) RMS as placed by the INS (the INS alone allows $(metric ins_floor_rgb_ate_m 100 cm)),"
echo "the trajectory's shape to $(metric rgb_ate_aligned_m 1000 mm) RMS once aligned, and the mesh to"
echo "$(metric mesh_accuracy_attitude_aligned_m 1000 mm) (median) with $(metric mesh_completeness_attitude_aligned 100 %) of the true seabed within 2 cm"
echo "(aligned with the frames' orientations: tiny's 0.7 m track is too short and straight"
echo "for its positions alone to fix the roll; docs/EVALUATE.md). The hyperspectral ortho-image"
echo "covers $(metric ortho_coverage 100 %) of the true footprint; its local distortion is"
echo "$(metric ortho_registration_rmse_m 1000 mm) RMS (needs enough textured 0.3 m patches; tiny has few)."
echo
echo "Open the run's report in a browser (one self-contained page, works offline):"
echo "report: $run/report/index.html"
