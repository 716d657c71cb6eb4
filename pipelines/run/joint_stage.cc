#include "pipelines/run/joint_stage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <ostream>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/utm_projection.h"
#include "core/io/atomic_file.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/util/stage_timer.h"
#include "pipelines/calibration/extrinsic_refinement.h"
#include "pipelines/calibration/strip_tie_points.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/georef/sequential_georef.h"
#include "pipelines/joint/joint_problem.h"
#include "pipelines/joint/joint_solution.h"
#include "pipelines/joint/joint_spline.h"
#include "pipelines/products/product_casting.h"
#include "pipelines/surface/surface_meshing.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

}  // namespace

void runJointStage(const StageContext& context, const JointStageOptions& options, SurfaceStageOptions surface) {
  options.validate();
  surface.validate();
  const Survey& survey = context.survey;
  std::ostream& out = context.out;
  if (!survey.cube) throw std::invalid_argument("the survey's UHI cube is not open");
  const UhiConfig& uhi = survey.config.uhi;
  const SE3d T_C_U_prior(uhi.T_C_U.rotation, uhi.T_C_U.translation_m);

  out << "joint: reading the front-end's files from " << (context.run / frontend_files::folder).string()
      << " and the sequential start from " << (context.run / stage_folders::georef).string() << "\n";
  const FrontendResult frontend = readFrontendOutputs(context.run);
  const GeorefResult georef = readGeorefOutputs(context.run / stage_folders::georef);

  // The spline through the sequential frame poses.
  std::vector<TimedPose> frames;
  for (const GeorefFramePose& frame : georef.frames) {
    if (frame.source == PoseSource::vision) frames.push_back({frame.t, frame.T_W_C});
  }
  if (frames.size() < 4) {
    throw std::runtime_error("the joint stage needs at least 4 frames posed by vision, got " +
                             std::to_string(frames.size()));
  }
  const KnotSpacingChoice spacing = chooseKnotSpacing(frames);
  out << "joint: " << spacing.reason << "\n";

  GeorefOptions georef_options;
  const InsBodyTrack ins(survey, georef_options.heading_window_s);
  JointInputs inputs;
  // The mesh was made from the sequential trajectory: its spline is the
  // tie points' reference (JointInputs::surface_trajectory).
  SE3Splined surface_spline = splineThroughPoses(frames, spacing.dt_s);
  inputs.spline = surface_spline;
  inputs.surface_trajectory = &surface_spline;
  VisualMap map_W = georef.map_W;
  inputs.map_W = &map_W;
  inputs.frontend = &frontend;
  inputs.frame_times = &survey.rgb.times();
  inputs.ins = &ins;
  for (const RejectedFix& rejected : georef.rejected_fixes) inputs.excluded_fixes.insert(rejected.fix);
  inputs.T_B_C = SE3d(survey.config.ins.T_B_C.rotation, survey.config.ins.T_B_C.translation_m);
  inputs.ins_noise = surveyInsNoise(survey, ins, georef_options);
  inputs.rgb_camera = survey.config.rgb.camera;
  inputs.uhi_camera = uhi.camera;
  // survey.yaml's uhi.camera_sigma: the intrinsics are estimated with T_C_U
  // and d (every sigma 0 or absent: held as given).
  if (uhi.camera_sigma) {
    inputs.uhi_intrinsics_sigma = {uhi.camera_sigma->f, uhi.camera_sigma->cx, uhi.camera_sigma->distortion[0],
                                   uhi.camera_sigma->distortion[1]};
  }
  if (inputs.estimatesUhiIntrinsics()) {
    out << "joint: uhi.camera_sigma is given: the UHI intrinsics are estimated with T_C_U and d\n";
  }
  inputs.T_C_U_prior = T_C_U_prior;
  inputs.sigma_rotation_deg = uhi.sigma_rotation_deg;
  inputs.sigma_translation_m = uhi.sigma_translation_m;
  inputs.time_offset_prior_s = uhi.time_offset_s;
  inputs.time_offset_sigma_s = uhi.time_offset_sigma_s;
  inputs.T_C_U_start = georef.T_C_U;
  inputs.time_offset_start_s = georef.time_offset_s;

  const UtmProjection projection(survey.origin);
  const fs::path surface_mesh = context.run / stage_folders::surface / stage_folders::mesh_ply;
  PlyMesh ply = readSurfaceMesh(surface_mesh);
  auto mesh = std::make_unique<MeshRayCaster>(ply.vertices, ply.triangles);
  const fs::path folder = context.run / stage_folders::joint;
  const fs::path scratch = AtomicFile::partialPathFor(folder.string() + "-cast");
  fs::remove_all(scratch);

  ExtrinsicRefinementOptions tie_options;
  tie_options.patch_spacing_m = options.ortho_patch_spacing_m;
  JointOptions joint_options;
  const double overlap = std::max(1.0, tie_options.patch_size_m / tie_options.patch_spacing_m);
  joint_options.sigma_match_m *= overlap;
  // The outlier gate stays where it was on the ground (3 x 5 mm over the range).
  joint_options.tie_robust_scale /= overlap;
  JointOptions strip_joint_options;
  strip_joint_options.sigma_match_m = options.strip_sigma_match_m;
  strip_joint_options.sigma_match_along_m = options.strip_sigma_match_along_m;
  // A strip column as wide as an RGB pixel (the prediction's resolution):
  // UHI samples per column = the two focal lengths' ratio (2 on the presets).
  StripTiePointOptions strip_options;
  strip_options.sample_step = std::max(1, int(std::lround(uhi.camera.f / survey.config.rgb.camera.fx)));
  // The UHI camera of the current estimate (survey.yaml's until a round
  // estimates the intrinsics): the strip's prediction and the scratch casts.
  PushbroomParameters uhi_current = uhi.camera;
  auto uhi_camera = std::make_unique<PushbroomCamera>(uhi_current);
  const PinholeRadtanCamera rgb_camera(survey.config.rgb.camera);

  // What the stage writes: the sequential start until a round is solved.
  GeorefResult posed = georef;
  posed.variant = "joint";
  RunCalibration calibration = georefCalibration(posed);
  std::vector<LinePose> line_poses;
  for (const GeorefLinePose& line : georef.lines) line_poses.push_back({line.line, line.t, line.T_W_U});
  BandCombination combination;
  bool combination_known = false;
  for (int round = 1; round <= options.rounds; ++round) {
    const auto round_start = std::chrono::steady_clock::now();
    out << "joint: round " << round << " of " << options.rounds << "\n";
    std::vector<ExtrinsicTiePoint> round_ties;
    // The strip's search reaches a few centimetres: the first round (a
    // guess up to degrees off) matches the ortho-images, coarse to fine.
    bool in_strip = round > 1 && options.tie_points == JointTiePoints::strip && combination_known;
    if (in_strip) {
      StripTiePointInputs strip;
      strip.cube = survey.cube.get();
      strip.band_weights = combination.weights;
      strip.band_offset = combination.offset;
      strip.uhi_camera = uhi_camera.get();
      strip.lines = line_poses;
      strip.mesh = mesh.get();
      strip.frames = &survey.rgb;
      strip.rgb_camera = &rgb_camera;
      for (int i = 0; i < survey.rgb.frameCount(); ++i) {
        const double t = survey.rgb.time(i);
        if (t >= inputs.spline.validBegin() && t <= inputs.spline.validEnd()) {
          strip.frame_poses.emplace_back(i, inputs.spline.pose(t));
        }
      }
      round_ties = findStripTiePoints(strip, strip_options, out).tie_points;
      if (int(round_ties.size()) < strip_joint_options.min_tie_points) {
        out << "joint: only " << round_ties.size() << " tie points in the strip (need "
            << strip_joint_options.min_tie_points << "); this round matches the ortho-images instead\n";
        in_strip = false;
      }
    }
    if (!in_strip) {
      out << "joint: casting the scan lines to match the ortho-images\n";
      castHyperspectralOrtho(survey, uhi_current, line_poses, *mesh, projection, scratch, options.cast_pixel_m, false, out);
      RunTiePoints found = collectOrthoTiePoints(scratch, ply, projection, tie_options, out);
      round_ties = std::move(found.tie_points);
      combination = std::move(found.combination);
      combination_known = true;
      fs::remove_all(scratch);
    }
    inputs.tie_points = jointTiePoints(round_ties, survey.line_times);
    const JointResult solved = solveJointProblem(inputs, in_strip ? strip_joint_options : joint_options);
    out << solved.summary();
    if (!solved.solved) {
      out << "warning: joint: round " << round << " not solved; "
          << (round == 1 ? "the sequential result (survey.yaml's T_C_U and d) stays in place"
                         : "the previous round's result stays in place")
          << "\n";
      if (round == 1) {
        calibration.warnings = {
            "T_C_U and time_offset_s are survey.yaml's guesses: the joint problem could not be solved"};
      }
      for (const std::string& warning : solved.warnings) {
        calibration.warnings.push_back("joint round " + std::to_string(round) + ": " + warning);
      }
      break;
    }
    const Sim3 G = ontoSurfaceFrame(solved.spline, surface_spline, frames);
    out << "joint: the solved trajectory brought back onto the surface's frame (georef's placement and "
           "scale) by a similarity of scale "
        << G.scale() << " and " << G.rotation().angularDistance(Eigen::Quaterniond::Identity()) * kRadToDeg
        << " deg\n";
    const JointResult joint = inSurfaceFrame(solved, G);
    const double rotation_change_deg = inputs.T_C_U_start.q.angularDistance(joint.T_C_U.q) * kRadToDeg;
    const double translation_change_m = (inputs.T_C_U_start.t - joint.T_C_U.t).norm();
    const double time_change_s = std::abs(inputs.time_offset_start_s - joint.time_offset_s);
    const auto [trajectory_change_m, trajectory_change_deg] =
        splineChange(inputs.spline, joint.spline, survey.rgb.times());
    out << "joint: round " << round << ": " << round_ties.size() << " tie points"
        << (in_strip ? " (in the strip)" : " (between the ortho-images)") << ", " << joint.tie_inliers
        << " inliers; T_C_U moved " << rotation_change_deg << " deg and " << translation_change_m * 1000.0
        << " mm, d moved " << time_change_s * 1000.0 << " ms, the trajectory " << trajectory_change_m * 1000.0
        << " mm and " << trajectory_change_deg << " deg (RMS over the frames)\n";

    posed = posedFromSpline(georef, joint, survey.line_times);
    calibration = jointCalibration(joint, round, georef.placement);
    line_poses.clear();
    for (const GeorefLinePose& line : posed.lines) line_poses.push_back({line.line, line.t, line.T_W_U});
    // The surface again from the joint trajectory, so the lines are cast
    // onto a mesh made with the same poses (and the next round's tie points
    // refer to it).
    out << "joint: meshing the surface again from the joint trajectory\n";
    ply = meshSurface(survey, withJointMap(posed, joint), surface.mode, surface.seabed_depth_m, out);
    mesh = std::make_unique<MeshRayCaster>(ply.vertices, ply.triangles);
    surface_spline = joint.spline;

    inputs.spline = joint.spline;
    for (const auto& [id, p_W] : joint.landmarks_W) map_W.landmark(id).p_F = p_W;
    inputs.T_C_U_start = joint.T_C_U;
    inputs.time_offset_start_s = joint.time_offset_s;
    if (joint.uhi_intrinsics) {
      inputs.uhi_intrinsics_start = joint.uhi_intrinsics;
      const auto& k = *joint.uhi_intrinsics;
      uhi_current.f = k[0];
      uhi_current.cx = k[1];
      uhi_current.distortion = {k[2], k[3]};
      uhi_camera = std::make_unique<PushbroomCamera>(uhi_current);
    }
    out << "joint: round " << round << " took " << secondsSince(round_start) << " s\n";
    if (!joint.time_offset_at_bound && rotation_change_deg < 0.005 && translation_change_m < 0.0005 &&
        time_change_s < 0.0002 && trajectory_change_m < 0.0005 && trajectory_change_deg < 0.005) {
      out << "joint: T_C_U, d and the trajectory stopped moving after round " << round << "\n";
      break;
    }
  }
  // The RGB intrinsics are georef's (rgb.camera_sigma), with its warnings.
  carryRgbCamera(readRunCalibration(context.run / stage_folders::georef / georef_files::calibration), calibration);
  writeGeorefOutputs(folder, posed, calibration);
  writePly(folder / stage_folders::mesh_ply, ply);
  out << "joint: wrote " << folder.string() << "/ (the trajectory, calibration.yaml, the map, mesh.ply: "
      << ply.triangles.size() << " triangles)\n";
}

}  // namespace hsmap
