#include "pipelines/run/refine_stage.h"

#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/geometry/utm_projection.h"
#include "core/io/atomic_file.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "pipelines/calibration/extrinsic_refinement.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/products/product_casting.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

SE3d toSe3(const RigidTransformConfig& T) { return SE3d(T.rotation, T.translation_m); }

}  // namespace

void runRefineStage(const StageContext& context, const RefineStageOptions& options) {
  options.validate();
  std::ostream& out = context.out;
  const Survey& survey = context.survey;
  const fs::path georef = context.run / stage_folders::georef;
  std::vector<LinePose> line_poses = readLinePoseTable(georef / georef_files::lines);
  RunCalibration calibration = readRunCalibration(georef / georef_files::calibration);
  std::ostringstream summary;

  const fs::path folder = context.run / stage_folders::refine;
  const fs::path staging = AtomicFile::partialPathFor(folder);
  fs::remove_all(staging);
  fs::create_directories(staging);
  if (options.rounds == 0) {
    summary << "refine: no round asked for (--extrinsic-rounds 0): T_C_U kept at survey.yaml's guess\n";
  } else {
    if (!survey.cube) throw std::invalid_argument("the survey's UHI cube is not open");
    const fs::path mesh_ply = context.run / stage_folders::surface / stage_folders::mesh_ply;
    out << "refine: scan line poses from " << (georef / georef_files::lines).string() << ", surface from "
        << mesh_ply.string() << "\n";
    const PlyMesh ply = readSurfaceMesh(mesh_ply);
    const MeshRayCaster mesh(ply.vertices, ply.triangles);
    const UtmProjection projection(survey.origin);
    const ExtrinsicPrior prior{toSe3(survey.config.uhi.T_C_U), survey.config.uhi.sigma_rotation_deg,
                               survey.config.uhi.sigma_translation_m, survey.config.uhi.time_offset_sigma_s};
    const fs::path cast = staging / "cast";
    for (int round = 1; round <= options.rounds; ++round) {
      const SE3d T_C_U_lines = toSe3(calibration.T_C_U);
      out << "refine: round " << round << " of " << options.rounds << ": casting the scan lines\n";
      castHyperspectralOrtho(survey, survey.config.uhi.camera, line_poses, mesh, projection, cast, options.cast_pixel_m, false, out);
      const ExtrinsicRefinementResult result =
          refineExtrinsicFromOrthoImages(cast, ply, line_poses, T_C_U_lines, survey.config.uhi.camera, prior,
                                         projection, ExtrinsicRefinementOptions{}, out);
      if (!result.refined) {
        summary << "refine: round " << round << ": T_C_U kept at "
                << (round == 1 ? "the survey's guess" : "the last round's result") << "\n";
        for (const auto& warning : result.warnings) {
          calibration.warnings.push_back("extrinsic refinement, round " + std::to_string(round) + ": " + warning);
        }
        break;
      }
      line_poses = updatedLinePoses(line_poses, T_C_U_lines, result.T_C_U);
      calibration.T_C_U.rotation = result.T_C_U.q;
      calibration.T_C_U.translation_m = result.T_C_U.t;
      calibration.sigma_rotation_deg = result.sigma_rotation_deg;
      calibration.sigma_translation_m = result.sigma_translation_m;
      calibration.warnings = {"T_C_U refined from the RGB and hyperspectral ortho-images (" +
                              std::to_string(result.inliers) + " tie points, round " + std::to_string(round) +
                              "); time_offset_s is the survey.yaml guess: the " + calibration.variant +
                              " variant does not estimate it, and T_C_U's 1-sigma includes what the guess's "
                              "own 1-sigma can move it by"};
      summary << "refine: round " << round << ": " << result.inliers << " tie points; T_C_U refined\n";
    }
    fs::remove_all(cast);
  }
  // The lever arm was measured in georef's map: as uncertain as its scale.
  if (fs::exists(georef / georef_files::map_placement)) {
    addMapScaleUncertainty(calibration, readMapPlacement(georef / georef_files::map_placement));
  }
  std::vector<TimedPose> lines_timed;
  lines_timed.reserve(line_poses.size());
  for (const LinePose& line : line_poses) lines_timed.push_back({line.t, line.T});
  writeLinePoseTable(staging / georef_files::lines, line_poses);
  writeTumTrajectory(staging / georef_files::lines_tum, lines_timed);
  // The RGB intrinsics are georef's (rgb.camera_sigma), with its warnings.
  carryRgbCamera(readRunCalibration(georef / georef_files::calibration), calibration);
  writeRunCalibration(staging / georef_files::calibration, calibration);
  writeTextAtomically(staging / georef_files::summary, summary.str());
  fs::remove_all(folder);
  fs::rename(staging, folder);
  out << summary.str() << "wrote " << folder.string() << "/\n";
}

}  // namespace hsmap
