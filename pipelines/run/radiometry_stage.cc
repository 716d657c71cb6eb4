#include "pipelines/run/radiometry_stage.h"

#include <algorithm>
#include <chrono>
#include <ostream>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/io/results_folder.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/survey/water_estimate.h"
#include "pipelines/products/hyperspectral_ortho.h"
#include "pipelines/radiometry/radiometric_observations.h"
#include "pipelines/radiometry/water_estimation.h"

namespace hsmap {

namespace fs = std::filesystem;

void runRadiometryStage(const StageContext& context) {
  std::ostream& out = context.out;
  const Survey& survey = context.survey;
  const fs::path folder = context.run / radiometry_files::folder;
  fs::create_directories(folder);
  fs::remove(folder / radiometry_files::water);
  if (!survey.config.lights) {
    const std::string why =
        "radiometry: survey.yaml has no `lights` block (the lamps and their response K(λ)): no reflectance, "
        "radiance products only\n";
    out << why;
    writeTextAtomically(folder / radiometry_files::summary, why);
    return;
  }
  if (!survey.cube) throw std::invalid_argument("the survey's UHI cube is not open");
  const fs::path lines_csv = context.run / results_paths::trajectory_uhi_lines;
  const fs::path mesh_ply = context.run / results_paths::mesh_ply;
  const fs::path calibration_yaml = context.run / results_paths::calibration_yaml;
  out << "radiometry: scan line poses from " << lines_csv.string() << ", surface from " << mesh_ply.string()
      << ", T_C_U from " << calibration_yaml.string() << "\n";
  const std::vector<LinePose> line_poses = readLinePoseTable(lines_csv);
  const PlyMesh ply = readSurfaceMesh(mesh_ply);
  const MeshRayCaster mesh(ply.vertices, ply.triangles);
  // The run's T_C_U and UHI camera; survey.yaml's guesses when no stage published an estimate.
  SE3d T_C_U(survey.config.uhi.T_C_U.rotation, survey.config.uhi.T_C_U.translation_m);
  PushbroomParameters uhi_camera = survey.config.uhi.camera;
  if (fs::exists(calibration_yaml)) {
    const RunCalibration calibration = readRunCalibration(calibration_yaml);
    T_C_U = SE3d(calibration.T_C_U.rotation, calibration.T_C_U.translation_m);
    if (calibration.uhi_camera) uhi_camera = calibration.uhi_camera->appliedTo(uhi_camera);
  }

  const auto start = std::chrono::steady_clock::now();
  ObservationOptions observation_options;
  // The solve's size is observations x bands residuals: at most ~1 200 000
  // (a 211-band cube: 355 points; 24 bands: the default 400): on rugged-uhi-off 177
  // points (600 000) gave c to 0.19 /m, 400 points (1.2 M) to 0.17 /m.
  observation_options.max_points = std::clamp(
      int(1200000 / (std::max(1, survey.cube->bands()) * observation_options.max_per_cell)), 50,
      observation_options.max_points);
  const RadiometricObservations observations = gatherObservations(
      *survey.cube, PushbroomCamera(uhi_camera), line_poses, mesh, *survey.config.lights, T_C_U, observation_options);
  const double gather_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream summary;
  summary << observations.summary() << "radiometry: observations gathered in " << gather_s << " s\n";
  if (observations.items.empty()) {
    summary << "warning: radiometry: no seabed point is seen by enough lit pixels: no reflectance\n";
    out << summary.str();
    writeTextAtomically(folder / radiometry_files::summary, summary.str());
    return;
  }
  const WaterEstimationReport report = estimateWater(observations, survey.lamp_response_dn, survey.wavelengths_nm);
  summary << report.summary(survey.wavelengths_nm);
  out << summary.str();
  writeWaterEstimate(folder / radiometry_files::water, report.water);
  if (fs::exists(calibration_yaml)) {
    // The run's calibration with the contract's `water:` block and the
    // stage's warnings, published as RUN/calibration.yaml.
    RunCalibration calibration = readRunCalibration(calibration_yaml);
    WaterEstimate water = report.water;
    for (const std::string& warning : water.warnings) {
      if (std::find(calibration.warnings.begin(), calibration.warnings.end(), warning) == calibration.warnings.end()) {
        calibration.warnings.push_back(warning);
      }
    }
    water.warnings.clear();
    calibration.water = water;
    writeRunCalibration(folder / radiometry_files::calibration, calibration);
  }
  writeTextAtomically(folder / radiometry_files::summary, summary.str());
  out << "wrote " << (folder / radiometry_files::water).string() << "\n";
}

}  // namespace hsmap
