#include "tools/hsmap/joint_stage.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>
#include <numbers>
#include <ostream>
#include <set>

#include "core/io/geotiff_export.h"
#include "core/io/ply_io.h"
#include "core/io/results_folder.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/util/stage_timer.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/georef/sequential_georef.h"
#include "pipelines/hyperspectral/extrinsic_refinement.h"
#include "pipelines/hyperspectral/strip_tie_points.h"
#include "pipelines/joint/joint_problem.h"
#include "pipelines/joint/joint_spline.h"
#include "tools/hsmap/run_stages.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

std::vector<JointTiePoint> jointTiePoints(const std::vector<ExtrinsicTiePoint>& found,
                                          const std::vector<double>& line_times) {
  std::vector<JointTiePoint> ties;
  ties.reserve(found.size());
  for (const ExtrinsicTiePoint& tie : found) {
    // The recorded time at the tie's continuous line position, between the
    // two lines around it.
    const double below = std::floor(tie.line_position);
    const double alpha = tie.line_position - below;
    if (!(below >= 0.0) || below + (alpha > 0.0 ? 1.0 : 0.0) >= double(line_times.size())) continue;
    const std::size_t a = std::size_t(below);
    const double t_recorded =
        alpha > 0.0 ? (1.0 - alpha) * line_times[a] + alpha * line_times[a + 1] : line_times[a];
    ties.push_back({tie.line, t_recorded, tie.sample, tie.range_m, tie.p_W});
  }
  return ties;
}

// The georef result with every frame and scan line posed from the spline
// where it is valid (elsewhere the sequential poses stay).
GeorefResult posedFromSpline(const GeorefResult& sequential, const JointResult& joint,
                             const std::vector<double>& line_times) {
  GeorefResult result = sequential;
  result.variant = "joint";
  const SE3Splined& spline = joint.spline;
  auto inSpline = [&](double t) { return t >= spline.validBegin() && t <= spline.validEnd(); };
  for (GeorefFramePose& frame : result.frames) {
    if (inSpline(frame.t)) frame.T_W_C = spline.pose(frame.t);
  }
  for (GeorefLinePose& line : result.lines) {
    const double t = line_times[std::size_t(line.line)] + joint.time_offset_s;
    line.t = t;
    if (inSpline(t)) {
      line.T_W_U = spline.pose(t) * joint.T_C_U;
    } else {
      // Outside the spline: the sequential camera pose, with the new extrinsic.
      line.T_W_U = line.T_W_U * sequential.T_C_U.inverse() * joint.T_C_U;
    }
  }
  result.T_C_U = joint.T_C_U;
  result.time_offset_s = joint.time_offset_s;
  result.landmarks_W.clear();
  for (const auto& [id, p_W] : joint.landmarks_W) result.landmarks_W.push_back(p_W);
  return result;
}

// The rigid motion G that brings the solved trajectory onto the one the
// surface was made with (least squares over the frames' positions,
// Eigen::umeyama without scale). The solve may settle the whole trajectory
// a few centimetres away (its absolute position is the INS's, to
// decimetres); T_C_U and d do not depend on that, but the scan lines must be
// cast onto the mesh in the mesh's own frame.
SE3d ontoSurfaceFrame(const SE3Splined& solved, const SE3Splined& surface,
                      const std::vector<TimedPose>& frames) {
  Eigen::Matrix3Xd from(3, Eigen::Index(frames.size())), to(3, Eigen::Index(frames.size()));
  Eigen::Index n = 0;
  for (const TimedPose& frame : frames) {
    if (frame.t < solved.validBegin() || frame.t > solved.validEnd()) continue;
    from.col(n) = solved.pose(frame.t).t;
    to.col(n) = surface.pose(frame.t).t;
    ++n;
  }
  if (n < 3) return SE3d();
  const Eigen::Matrix4d G = Eigen::umeyama(from.leftCols(n), to.leftCols(n), false);
  return SE3d(Eigen::Quaterniond(Eigen::Matrix3d(G.topLeftCorner<3, 3>())).normalized(),
              G.topRightCorner<3, 1>());
}

JointResult inSurfaceFrame(JointResult joint, const SE3d& G) {
  std::vector<SE3d> control_points;
  for (const SE3d& T : joint.spline.controlPoints()) control_points.push_back(G * T);
  joint.spline = SE3Splined(joint.spline.t0(), joint.spline.dt(), std::move(control_points));
  for (auto& [id, p_W] : joint.landmarks_W) p_W = G * p_W;
  return joint;
}

// The sparse map of the sequential result with the joint keyframe poses and
// landmarks, for the surface stage.
GeorefResult withJointMap(GeorefResult posed, const JointResult& joint) {
  const SE3Splined& spline = joint.spline;
  for (const Keyframe& keyframe : posed.map_W.keyframes()) {
    if (keyframe.t >= spline.validBegin() && keyframe.t <= spline.validEnd()) {
      posed.map_W.keyframe(keyframe.id).T_F_C = spline.pose(keyframe.t);
    }
  }
  for (const auto& [id, p_W] : joint.landmarks_W) posed.map_W.landmark(id).p_F = p_W;
  return posed;
}

RunCalibration jointCalibration(const JointResult& joint, int round) {
  RunCalibration calibration;
  calibration.variant = "joint";
  calibration.T_C_U.rotation = joint.T_C_U.q;
  calibration.T_C_U.translation_m = joint.T_C_U.t;
  calibration.sigma_rotation_deg = joint.sigma_rotation_deg;
  calibration.sigma_translation_m = joint.sigma_translation_m;
  calibration.time_offset_s = joint.time_offset_s;
  calibration.time_offset_sigma_s = joint.time_offset_sigma_s;
  calibration.warnings.push_back("T_C_U and time_offset_s estimated by the joint problem (round " +
                                 std::to_string(round) + ", " + std::to_string(joint.tie_inliers) +
                                 " cross-modal tie points)");
  for (const std::string& component : joint.weakly_determined) {
    calibration.warnings.push_back("observability: " + component +
                                   " is weakly determined by this survey (its 1-sigma is more "
                                   "than half the prior's); it stays close to survey.yaml's guess");
  }
  for (const std::string& warning : joint.warnings) calibration.warnings.push_back(warning);
  return calibration;
}

}  // namespace

void runJointStage(const Survey& survey, const FrontendResult& frontend, const GeorefResult& georef,
                   const RunOptions& options, std::ostream& out) {
  if (!survey.cube) throw std::invalid_argument("the survey's UHI cube is not open");
  const UhiConfig& uhi = survey.config.uhi;
  const SE3d T_C_U_prior(uhi.T_C_U.rotation, uhi.T_C_U.translation_m);

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
  inputs.T_C_U_prior = T_C_U_prior;
  inputs.sigma_rotation_deg = uhi.sigma_rotation_deg;
  inputs.sigma_translation_m = uhi.sigma_translation_m;
  inputs.time_offset_prior_s = uhi.time_offset_s;
  inputs.time_offset_sigma_s = uhi.time_offset_sigma_s;
  inputs.T_C_U_start = georef.T_C_U;
  inputs.time_offset_start_s = georef.time_offset_s;

  const UtmProjection projection(survey.origin);
  PlyMesh ply = readSurfaceMesh(options.out / results_paths::mesh_ply);
  const fs::path calibration_yaml = options.out / results_paths::calibration_yaml;
  // The joint stage rewrites the trajectory, the surface and the products:
  // run again on a finished joint run (--from joint), it starts from that
  // result (a warm start), not from the sequential one. Only a joint solve
  // writes d's 1-sigma, so calibration.yaml tells which it is.
  if (fs::exists(calibration_yaml) && readRunCalibration(calibration_yaml).time_offset_sigma_s) {
    out << "warning: joint: the surface and products in " << options.out.string()
        << " are an earlier joint stage's: this run starts from them, not from the sequential "
           "result (--from georef starts again from it)\n";
  }
  HyperspectralReport report;
  bool cast = false;
  // A lattice twice as dense as the sequential refinement's: T_C_U's
  // translation is seen only through the relief's range differences, so the
  // joint problem needs every confident match it can get.
  ExtrinsicRefinementOptions tie_options;
  tie_options.patch_spacing_m = 0.075;
  // Neighbouring patches overlap (0.20 m windows every 0.075 m share most of
  // their pixels), so their match errors are correlated: each tie point is
  // weighted as if it held only its share of a window, the match sigma
  // inflated by patch size / spacing (the square root of the ~7 windows
  // that cover each pixel). Without this the 1-sigma of T_C_U came out
  // 3-4 times too small on low-relief.
  // The outlier gate stays where it was on the ground (3 x 5 mm over the range).
  JointOptions joint_options;
  const double overlap = std::max(1.0, tie_options.patch_size_m / tie_options.patch_spacing_m);
  joint_options.sigma_match_m *= overlap;
  joint_options.tie_robust_scale /= overlap;
  // Tie points matched in the push-broom strip (rounds after the first):
  // patches that do not overlap, so no inflation; finer across the track
  // (the sensors' own pixels) than along it (the lines' spacing): 2 mm is
  // three quarters of the strip's pixel on the presets, 5 mm a third of the
  // line spacing. Their residuals after the solve scatter ten times less;
  // the errors all tie points share (the frames' poses, the surface) set
  // their precision, not the matching (docs/JOINT.md, "Weights").
  JointOptions strip_joint_options;
  strip_joint_options.sigma_match_m = 0.002;
  strip_joint_options.sigma_match_along_m = 0.005;
  // A strip column as wide as an RGB pixel (the prediction's resolution):
  // UHI samples per column = the two focal lengths' ratio (2 on the presets).
  StripTiePointOptions strip_options;
  strip_options.sample_step =
      std::max(1, int(std::lround(uhi.camera.f / survey.config.rgb.camera.fx)));
  const PushbroomCamera uhi_camera(uhi.camera);
  const PinholeRadtanCamera rgb_camera(survey.config.rgb.camera);
  BandCombination combination;
  std::vector<LinePose> line_poses;
  std::unique_ptr<MeshRayCaster> mesh;
  for (int round = 1; round <= options.joint_rounds; ++round) {
    const auto round_start = std::chrono::steady_clock::now();
    out << "joint: round " << round << " of " << options.joint_rounds << "\n";
    std::vector<ExtrinsicTiePoint> round_ties;
    // The strip's search reaches a few centimetres: the first round (a
    // guess up to degrees off) matches the ortho-images, coarse to fine.
    bool in_strip = round > 1 && options.joint_tie_points == "strip" && mesh != nullptr;
    if (in_strip) {
      StripTiePointInputs strip;
      strip.cube = survey.cube.get();
      strip.band_weights = combination.weights;
      strip.band_offset = combination.offset;
      strip.uhi_camera = &uhi_camera;
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
            << strip_joint_options.min_tie_points
            << "); this round matches the ortho-images instead\n";
        in_strip = false;
      }
    }
    if (!in_strip) {
      RunTiePoints found = collectTiePointsInRun(options.out, projection, tie_options, out);
      round_ties = std::move(found.tie_points);
      combination = std::move(found.combination);
    }
    inputs.tie_points = jointTiePoints(round_ties, survey.line_times);
    const JointResult solved = solveJointProblem(inputs, in_strip ? strip_joint_options : joint_options);
    out << solved.summary();
    const SE3d G = ontoSurfaceFrame(solved.spline, surface_spline, frames);
    if (solved.solved) {
      out << "joint: the solved trajectory moved " << G.t.norm() * 1000.0 << " mm and "
          << G.q.angularDistance(Eigen::Quaterniond::Identity()) * kRadToDeg
          << " deg as a whole from the surface's frame; brought back onto it\n";
    }
    const JointResult joint = solved.solved ? inSurfaceFrame(solved, G) : solved;
    if (!joint.solved) {
      out << "warning: joint: round " << round << " not solved; "
          << (round == 1 ? "the sequential result (survey.yaml's T_C_U and d) stays in place"
                         : "the previous round's result stays in place")
          << "\n";
      RunCalibration calibration = readRunCalibration(calibration_yaml);
      calibration.variant = "joint";
      if (round == 1) {
        calibration.warnings = {
            "T_C_U and time_offset_s are survey.yaml's guesses: the joint problem could not be solved"};
      }
      for (const std::string& warning : joint.warnings) {
        calibration.warnings.push_back("joint round " + std::to_string(round) + ": " + warning);
      }
      writeRunCalibration(calibration_yaml, calibration);
      break;
    }
    const double rotation_change_deg =
        inputs.T_C_U_start.q.angularDistance(joint.T_C_U.q) * kRadToDeg;
    const double translation_change_m = (inputs.T_C_U_start.t - joint.T_C_U.t).norm();
    const double time_change_s = std::abs(inputs.time_offset_start_s - joint.time_offset_s);
    const auto [trajectory_change_m, trajectory_change_deg] =
        splineChange(inputs.spline, joint.spline, survey.rgb.times());
    out << "joint: round " << round << ": " << round_ties.size() << " tie points"
        << (in_strip ? " (in the strip)" : " (between the ortho-images)") << ", "
        << joint.tie_inliers << " inliers; T_C_U moved " << rotation_change_deg << " deg and "
        << translation_change_m * 1000.0 << " mm, d moved " << time_change_s * 1000.0
        << " ms, the trajectory " << trajectory_change_m * 1000.0 << " mm and "
        << trajectory_change_deg << " deg (RMS over the frames)\n";

    const GeorefResult posed = posedFromSpline(georef, joint, survey.line_times);
    writeGeorefOutputs(options.out, posed);
    writeRunCalibration(calibration_yaml, jointCalibration(joint, round));
    line_poses.clear();
    for (const GeorefLinePose& line : posed.lines) line_poses.push_back({line.line, line.t, line.T_W_U});
    // The surface again from the joint trajectory, so the lines are cast
    // onto a mesh made with the same poses (and the next round's tie points
    // refer to it).
    out << "joint: wrote the trajectory and calibration.yaml; rebuilding the surface\n";
    runSurfaceStage(survey, withJointMap(posed, joint), options, out);
    ply = readSurfaceMesh(options.out / results_paths::mesh_ply);
    surface_spline = joint.spline;
    out << "joint: casting the scan lines again\n";
    mesh = std::make_unique<MeshRayCaster>(ply.vertices, ply.triangles);
    report = castProducts(survey, line_poses, *mesh, projection, options, false, out);
    cast = true;

    inputs.spline = joint.spline;
    for (const auto& [id, p_W] : joint.landmarks_W) map_W.landmark(id).p_F = p_W;
    inputs.T_C_U_start = joint.T_C_U;
    inputs.time_offset_start_s = joint.time_offset_s;
    out << "joint: round " << round << " took " << secondsSince(round_start) << " s\n";
    const bool bound_reached = std::any_of(joint.warnings.begin(), joint.warnings.end(),
                                           [](const std::string& w) { return w.find("bound") != std::string::npos; });
    if (!bound_reached && rotation_change_deg < 0.005 && translation_change_m < 0.0005 &&
        time_change_s < 0.0002 && trajectory_change_m < 0.0005 && trajectory_change_deg < 0.005) {
      out << "joint: T_C_U, d and the trajectory stopped moving after round " << round << "\n";
      break;
    }
  }
  if (options.geotiff) {
    const auto start = std::chrono::steady_clock::now();
    exportEnviToCog(options.out / "hyperspectral/ortho.hdr", options.out / "hyperspectral/ortho.tif",
                    HyperspectralOptions{}.geotiff);
    out << "joint: GeoTIFF written in " << secondsSince(start) << " s\n";
  }
  if (cast) writeRgbOrthoProducts(ply, *mesh, report.grid, projection, options, out);
}

}  // namespace hsmap
