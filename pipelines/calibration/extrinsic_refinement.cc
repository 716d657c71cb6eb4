#include "pipelines/calibration/extrinsic_refinement.h"

#include <ostream>

namespace hsmap {

std::vector<LinePose> updatedLinePoses(const std::vector<LinePose>& line_poses,
                                       const SE3d& T_C_U_lines, const SE3d& T_C_U_new) {
  const SE3d T_U_lines_U_new = T_C_U_lines.inverse() * T_C_U_new;
  std::vector<LinePose> out = line_poses;
  for (LinePose& pose : out) {
    pose.T = pose.T * T_U_lines_U_new;
    pose.T.q.normalize();
  }
  return out;
}

ExtrinsicRefinementResult refineExtrinsicFromOrthoImages(
    const std::filesystem::path& ortho_folder, const PlyMesh& mesh, const std::vector<LinePose>& line_poses,
    const SE3d& T_C_U_lines, const PushbroomParameters& camera, const ExtrinsicPrior& prior,
    const UtmProjection& projection, const ExtrinsicRefinementOptions& options, std::ostream& log) {
  const RunTiePoints found = collectOrthoTiePoints(ortho_folder, mesh, projection, options, log);
  ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      found.tie_points, line_poses, T_C_U_lines, camera, prior, options);
  result.patches = found.counts.patches;
  result.matches = found.counts.matched;
  result.band_weights = found.combination.weights;
  result.band_offset = found.combination.offset;
  result.band_fit_r2 = found.combination.fitted ? found.combination.r2 : 0.0;
  result.median_shift_m = found.median_shift_m;
  log << result.summary();
  return result;
}

}  // namespace hsmap
