#include "pipelines/evaluate/evaluate_run.h"

#include <stdexcept>

#include "core/geometry/pushbroom_camera.h"
#include "core/io/atomic_file.h"
#include "core/io/ply_io.h"
#include "core/io/results_folder.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/calibration_metrics.h"
#include "pipelines/evaluate/ins_floor.h"
#include "pipelines/evaluate/mesh_metrics.h"
#include "pipelines/evaluate/ortho_metrics.h"
#include "pipelines/evaluate/ortho_pixel_error.h"
#include "pipelines/evaluate/reflectance_metrics.h"
#include "pipelines/evaluate/trajectory_metrics.h"
#include "pipelines/evaluate/view_distance.h"

namespace hsmap {

namespace {

// The contract's reflectance keys: null, saying why (the measurement, when
// the run has a reflectance product, replaces them).
void markNoReflectance(EvaluationMetrics& metrics, const std::string& why) {
  const MetricValue none = MetricValue::missing(why);
  for (MetricValue* m : {&metrics.reflectance_sam_deg, &metrics.reflectance_rmse, &metrics.reflectance_gain_free_rmse,
                         &metrics.water_attenuation_rmse_per_m}) {
    *m = none;
  }
}

// The UHI and RGB intrinsics the run used (calibration.yaml's uhi_camera
// and rgb_camera, or survey.yaml's) against the truth: they shape every
// variant's products.
void measureUhiIntrinsics(const EvaluationInputs& inputs, EvaluationMetrics& metrics) {
  const CalibrationErrors errors = compareCalibration(inputs.calibration, inputs.survey.config.uhi.camera,
                                                      inputs.survey.config.rgb.camera, inputs.truth.calibration);
  metrics.rgb_focal_error_rel = MetricValue::of(errors.rgb_focal_error_rel);
  metrics.rgb_cx_error_px = MetricValue::of(errors.rgb_cx_error_px);
  metrics.rgb_cy_error_px = MetricValue::of(errors.rgb_cy_error_px);
  metrics.uhi_focal_error_rel = MetricValue::of(errors.uhi_focal_error_rel);
  metrics.uhi_cx_error_px = MetricValue::of(errors.uhi_cx_error_px);
  for (std::size_t i = 0; i < 2; ++i) metrics.uhi_distortion_error[i] = MetricValue::of(errors.uhi_distortion_error[i]);
}

// A stacked run: scan lines side by side, nothing posed or placed.
EvaluationMetrics stackedMetrics(const EvaluationInputs& inputs) {
  EvaluationMetrics metrics;
  metrics.variant = inputs.run.variant;
  const MetricValue none = MetricValue::missing(kStackedHasNoPoses);
  for (MetricValue* m :
       {&metrics.rgb_ate_m, &metrics.rgb_ate_aligned_m, &metrics.rgb_scale_error, &metrics.uhi_position_rmse_m,
        &metrics.uhi_rotation_rmse_deg, &metrics.extrinsic_rotation_error_deg,
        &metrics.extrinsic_translation_error_m, &metrics.time_offset_error_s, &metrics.mesh_accuracy_m,
        &metrics.mesh_completeness, &metrics.mesh_accuracy_attitude_aligned_m,
        &metrics.mesh_completeness_attitude_aligned, &metrics.alignment_cross_track_spread_m,
        &metrics.ortho_mean_shift_m, &metrics.ortho_registration_rmse_m, &metrics.ortho_scale_error,
        &metrics.ortho_sam_deg, &metrics.ortho_coverage, &metrics.ortho_pixel_error_m,
        &metrics.ortho_pixel_error_abs_m, &metrics.ins_floor_rgb_ate_m, &metrics.ins_floor_scale_error,
        &metrics.alignment_view_distance_m, &metrics.uhi_position_rmse_positions_aligned_m,
        &metrics.uhi_rotation_rmse_positions_aligned_deg, &metrics.mesh_accuracy_positions_aligned_m,
        &metrics.mesh_completeness_positions_aligned}) {
    *m = none;
  }
  measureUhiIntrinsics(inputs, metrics);
  const MetricValue no_rgb = MetricValue::missing(kStackedUsesNoRgbCamera);
  for (MetricValue* m : {&metrics.rgb_focal_error_rel, &metrics.rgb_cx_error_px, &metrics.rgb_cy_error_px}) *m = no_rgb;
  markNoReflectance(metrics, kStackedMakesNoReflectance);
  for (const StageRecord& stage : inputs.run.stages) metrics.timings_s.emplace_back(stage.name, stage.time_s);
  metrics.timings_s.emplace_back("total", inputs.run.total_time_s);
  metrics.peak_rss_mb = MetricValue::of(inputs.run.peak_rss_mb);
  return metrics;
}

// A ray caster on truth/scene.ply (the PLY itself is freed on return: the
// caster keeps its own copy).
MeshRayCaster trueSceneCaster(const std::filesystem::path& scene_path) {
  const PlyMesh scene = readPly(scene_path);
  if (scene.triangles.empty()) {
    throw InputError(scene_path, "", "has no triangles: expected the true surface as a triangle mesh");
  }
  try {
    return MeshRayCaster(scene.vertices, scene.triangles);
  } catch (const std::invalid_argument& e) {
    throw InputError(scene_path, "", std::string("not a usable true surface: ") + e.what());
  }
}

}  // namespace

EvaluationMetrics evaluateRun(const EvaluationInputs& inputs) {
  if (inputs.run.variant == "stacked") return stackedMetrics(inputs);
  EvaluationMetrics metrics;
  metrics.variant = inputs.run.variant;

  std::vector<TimedPose> frames_true;
  for (const TruthPose& pose : inputs.truth.rgb_poses) frames_true.push_back({pose.t, pose.T_W_X});
  std::vector<LinePose> lines_true;
  for (const TruthLinePose& pose : inputs.truth.uhi_poses) {
    lines_true.push_back({pose.line, pose.t, pose.T_W_U});
  }
  std::vector<SE3d> T_W_U_true;
  for (const LinePose& pose : lines_true) T_W_U_true.push_back(pose.T);

  // The rays on the true surface: the view distance of the frames' view
  // Sim(3) and the ortho pixels' true seen points. The caster (Embree's BVH)
  // is freed before the mesh metrics build their distance trees (memory).
  TrajectoryMetrics trajectory;
  OrthoPixelError pixel_error;
  {
    const MeshRayCaster true_scene = trueSceneCaster(inputs.truth.scene_path);
    const ViewDistance view_distance = medianViewDistance(frames_true, true_scene);
    trajectory = computeTrajectoryMetrics(inputs.frames, frames_true, inputs.lines, lines_true,
                                          view_distance.h_m);
    pixel_error = measureRunOrthoPixelError(
        inputs.run_folder / results_paths::ortho_hdr, inputs.run_folder / results_paths::ancillary_hdr,
        T_W_U_true, PushbroomCamera(inputs.truth.calibration.uhi_camera), true_scene, inputs.survey.origin);
  }
  metrics.rgb_ate_m = trajectory.rgb_ate_m;
  metrics.rgb_ate_aligned_m = trajectory.rgb_ate_aligned_m;
  metrics.rgb_scale_error = trajectory.rgb_scale_error;
  metrics.uhi_position_rmse_m = trajectory.uhi_position_rmse_m;
  metrics.uhi_rotation_rmse_deg = trajectory.uhi_rotation_rmse_deg;
  metrics.alignment_cross_track_spread_m = trajectory.alignment_cross_track_spread_m;
  metrics.alignment_view_distance_m = trajectory.alignment_view_distance_m;
  metrics.uhi_position_rmse_positions_aligned_m = trajectory.uhi_position_rmse_positions_aligned_m;
  metrics.uhi_rotation_rmse_positions_aligned_deg = trajectory.uhi_rotation_rmse_positions_aligned_deg;

  const CalibrationErrors calibration =
      compareCalibration(inputs.calibration, inputs.survey.config.uhi.camera, inputs.truth.calibration);
  measureUhiIntrinsics(inputs, metrics);
  markNoReflectance(metrics, "not measured");
  metrics.extrinsic_rotation_error_deg = MetricValue::of(calibration.extrinsic_rotation_error_deg);
  metrics.extrinsic_translation_error_m =
      MetricValue::of(calibration.extrinsic_translation_error_m);
  metrics.time_offset_error_s = MetricValue::of(calibration.time_offset_error_s);

  // The mesh is judged in the frame the frames' alignment defines; without
  // that alignment there is no frame to judge it in, for the same reason.
  // The contract's view Sim(3) first, then the positions-only and the
  // attitude-anchored alignments (extensions).
  const std::vector<MeshMetrics> mesh = measureRunMesh(
      inputs.run_folder / results_paths::mesh_ply,
      {{trajectory.S_true_est_view, trajectory.why_no_view_alignment},
       {trajectory.S_true_est, trajectory.why_no_alignment},
       {trajectory.S_true_est_attitude, trajectory.why_no_attitude_alignment}},
      inputs.truth.scene_path, inputs.truth.reflectance_header_path);
  metrics.mesh_accuracy_m = mesh[0].mesh_accuracy_m;
  metrics.mesh_completeness = mesh[0].mesh_completeness;
  metrics.mesh_accuracy_positions_aligned_m = mesh[1].mesh_accuracy_m;
  metrics.mesh_completeness_positions_aligned = mesh[1].mesh_completeness;
  metrics.mesh_accuracy_attitude_aligned_m = mesh[2].mesh_accuracy_m;
  metrics.mesh_completeness_attitude_aligned = mesh[2].mesh_completeness;

  // The ortho-image as placed (its geo-referencing is one of its metrics),
  // in the survey's UTM zone through W's origin.
  const OrthoMetrics ortho =
      measureRunOrtho(inputs.run_folder / results_paths::ortho_hdr,
                      inputs.truth.reflectance_header_path, inputs.survey.origin);
  metrics.ortho_mean_shift_m = ortho.ortho_mean_shift_m;
  metrics.ortho_registration_rmse_m = ortho.ortho_registration_rmse_m;
  metrics.ortho_scale_error = ortho.ortho_scale_error;
  metrics.ortho_sam_deg = ortho.ortho_sam_deg;
  metrics.ortho_coverage = ortho.ortho_coverage;
  if (ortho.patch_pixels > 0) {  // measured
    const std::string summary = ortho.summary();
    metrics.ortho_patches = summary.substr(0, summary.find('\n'));
  }
  metrics.ortho_matches = ortho.matches;
  // The reflectance product and the water estimate, when the run made them
  // (the radiometry stage; docs/RADIOMETRY.md), spectra compared at the
  // ortho's registered position.
  const ReflectanceMetrics reflectance =
      measureRunReflectance(inputs.run_folder, inputs.truth.reflectance_header_path,
                            inputs.truth.calibration.water_attenuation_per_m, inputs.survey.origin, ortho.matches);
  metrics.reflectance_sam_deg = reflectance.reflectance_sam_deg;
  metrics.reflectance_rmse = reflectance.reflectance_rmse;
  metrics.reflectance_gain_free_rmse = reflectance.reflectance_gain_free_rmse;
  metrics.water_attenuation_rmse_per_m = reflectance.water_attenuation_rmse_per_m;
  metrics.ortho_pixel_error_m = pixel_error.ortho_pixel_error_m;
  metrics.ortho_pixel_error_abs_m = pixel_error.ortho_pixel_error_abs_m;
  if (pixel_error.patch_pixels > 0) metrics.ortho_pixel_counts = pixel_error.summary();

  for (const StageRecord& stage : inputs.run.stages) {
    metrics.timings_s.emplace_back(stage.name, stage.time_s);
  }
  metrics.timings_s.emplace_back("total", inputs.run.total_time_s);
  metrics.peak_rss_mb = MetricValue::of(inputs.run.peak_rss_mb);

  const InsFloor floor =
      computeInsFloor(frames_true, insFixesInWorld(inputs.survey), inputs.survey.config.ins);
  metrics.ins_floor_rgb_ate_m = floor.rgb_ate_m;
  metrics.ins_floor_scale_error = floor.scale_error;
  return metrics;
}

EvaluationReport evaluateRunFolder(const std::filesystem::path& run_folder,
                                   const std::filesystem::path& truth_folder) {
  const EvaluationInputs inputs = loadEvaluationInputs(run_folder, truth_folder);
  EvaluationReport report;
  report.metrics = evaluateRun(inputs);
  report.warnings = inputs.warnings;
  report.metrics_path = run_folder / results_paths::metrics_json;
  if (!report.metrics.ortho_matches.empty()) {
    report.ortho_patches_path = run_folder / results_paths::report_dir / "ortho_patches.csv";
    std::filesystem::create_directories(report.ortho_patches_path.parent_path());
    AtomicFile patches(report.ortho_patches_path);
    patches.stream() << "north_m,east_m,displacement_north_m,displacement_east_m,response\n";
    for (const OrthoPatchMatch& match : report.metrics.ortho_matches) {
      patches.stream() << formatDouble(match.centre_NE.x()) << ',' << formatDouble(match.centre_NE.y())
                       << ',' << formatDouble(match.displacement_NE.x()) << ','
                       << formatDouble(match.displacement_NE.y()) << ','
                       << formatDouble(match.response) << '\n';
    }
    patches.commit();
  }
  AtomicFile out(report.metrics_path);
  out.stream() << metricsJson(report.metrics);
  out.commit();
  return report;
}

}  // namespace hsmap
