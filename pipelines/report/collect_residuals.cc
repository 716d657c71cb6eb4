#include "pipelines/report/collect_residuals.h"

#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pose_interpolation.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "core/util/input_error.h"
#include "pipelines/georef/georef_bundle_adjuster.h"
#include "pipelines/report/collect_trajectory.h"
#include "pipelines/report/named_csv.h"
#include "pipelines/report/report_histogram.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

// Every observation's reprojection error (px) in a map folder of
// visual_map_files.h's format, or nothing when a file is missing.
std::vector<double> reprojectionErrors(const fs::path& folder, const PinholeRadtanCamera& camera) {
  std::error_code error;
  for (const char* name : {"keyframes.csv", "landmarks.csv", "observations.csv"}) {
    if (!fs::is_regular_file(folder / name, error)) return {};
  }
  const NamedCsv keyframes(folder / "keyframes.csv", {"keyframe", "x", "y", "z", "qw", "qx", "qy", "qz"});
  std::unordered_map<long long, SE3d> T_C_M;  // map frame M (F or W) into each keyframe's camera
  for (std::size_t row = 0; row < keyframes.rowCount(); ++row) {
    const Eigen::Quaterniond q(keyframes.number(row, "qw"), keyframes.number(row, "qx"), keyframes.number(row, "qy"),
                               keyframes.number(row, "qz"));
    const Eigen::Vector3d t(keyframes.number(row, "x"), keyframes.number(row, "y"), keyframes.number(row, "z"));
    T_C_M[keyframes.integer(row, "keyframe")] = SE3d(q.normalized(), t).inverse();
  }
  const NamedCsv landmarks(folder / "landmarks.csv", {"landmark", "x", "y", "z"});
  std::unordered_map<long long, Eigen::Vector3d> p_M;
  for (std::size_t row = 0; row < landmarks.rowCount(); ++row) {
    p_M[landmarks.integer(row, "landmark")] =
        Eigen::Vector3d(landmarks.number(row, "x"), landmarks.number(row, "y"), landmarks.number(row, "z"));
  }
  const NamedCsv observations(folder / "observations.csv", {"keyframe", "landmark", "u", "v"});
  std::vector<double> errors;
  errors.reserve(observations.rowCount());
  for (std::size_t row = 0; row < observations.rowCount(); ++row) {
    const auto pose = T_C_M.find(observations.integer(row, "keyframe"));
    const auto point = p_M.find(observations.integer(row, "landmark"));
    if (pose == T_C_M.end() || point == p_M.end()) {
      throw InputError(observations.file(), InputError::atLine(observations.lineNumber(row)),
                       "observes keyframe " + observations.text(row, "keyframe") + " and landmark " +
                           observations.text(row, "landmark") + ": expected both in keyframes.csv and landmarks.csv");
    }
    const Eigen::Vector3d p_C = pose->second * point->second;
    if (!(p_C.z() > 0.0)) {
      errors.push_back(NAN);
      continue;
    }
    const Eigen::Vector2d uv(observations.number(row, "u"), observations.number(row, "v"));
    errors.push_back((camera.project(p_C) - uv).norm());
  }
  return errors;
}

}  // namespace

void collectResiduals(const fs::path& run, const Survey* survey, ReportData& data) {
  if (survey == nullptr) {
    data.notes.push_back("no residual histograms: they need the survey's cameras and INS (the survey folder " +
                         data.survey_folder + " could not be read)");
    return;
  }
  const GeorefBundleOptions bundle;  // the options geo-referencing runs with
  const double huber_px = bundle.pixel_sigma_px * bundle.huber_sigmas;
  const PinholeRadtanCamera camera(survey->config.rgb.camera);
  const std::string huber_meaning = "beyond the Huber loss's " + std::to_string(int(std::lround(huber_px))) +
                                    " px the adjustment down-weights an observation";
  const auto add_reprojection = [&](const std::string& name, const fs::path& folder) {
    const std::vector<double> errors = reprojectionErrors(folder, camera);
    if (errors.empty()) {
      data.notes.push_back("no histogram of the " + name + ": " + folder.string() +
                           " has no keyframes.csv, landmarks.csv and observations.csv");
      return;
    }
    std::vector<bool> outlier(errors.size());
    for (std::size_t i = 0; i < errors.size(); ++i) outlier[i] = errors[i] > huber_px;
    data.histograms.push_back(binResiduals(name, "px", errors, outlier, huber_px, huber_meaning));
  };
  if (data.variant != "planar" && data.variant != "stacked") {
    add_reprojection("reprojection error, front-end's map (before geo-referencing)", run / "frontend");
    add_reprojection(std::string("reprojection error, adjusted map (after ") +
                         (data.variant == "joint" ? "the joint solve)" : "geo-referencing)"),
                     adjustedMapFolder(run, data.variant));
  }

  // INS: the fix against the body on the trajectory.
  if (data.frames.size() < 2 || data.ins_fixes.empty()) {
    data.notes.push_back("no INS residuals: they need trajectory/frames.csv and the survey's INS fixes");
    return;
  }
  const fs::path frames_csv = run / "trajectory" / "frames.csv";
  std::vector<double> times;
  std::vector<SE3d> poses;
  for (const TimedPose& pose : readTimedPoseTable(frames_csv)) {
    times.push_back(pose.t);
    poses.push_back(pose.T);
  }
  const TimedPoseTrajectory trajectory(std::move(times), std::move(poses));
  const RigidTransformConfig& mounting = survey->config.ins.T_B_C;
  const SE3d T_C_B = SE3d(mounting.rotation, mounting.translation_m).inverse();
  std::vector<double> horizontal, depth;
  std::vector<bool> rejected;
  for (const ReportInsFix& fix : data.ins_fixes) {
    if (!trajectory.covers(fix.position.t)) continue;
    const Eigen::Vector3d p_W_B = (trajectory.at(fix.position.t) * T_C_B).t;
    const Eigen::Vector3d d = Eigen::Vector3d(fix.position.north, fix.position.east, fix.position.down) - p_W_B;
    horizontal.push_back(std::hypot(d.x(), d.y()));
    depth.push_back(std::abs(d.z()));
    rejected.push_back(fix.rejected);
  }
  if (horizontal.empty()) {
    data.notes.push_back("no INS residuals: no INS fix falls within the trajectory's time span");
    return;
  }
  const std::string meaning = "fixes geo-referencing left out (georef/rejected_fixes.csv)";
  const auto sigma_text = [](double sigma_m) {
    char text[64];
    std::snprintf(text, sizeof(text), " (stated 1-sigma %.3g m)", sigma_m);
    return std::string(text);
  };
  data.histograms.push_back(binResiduals("INS fix to trajectory, horizontal" +
                                             sigma_text(survey->config.ins.sigma_horizontal_m),
                                         "m", horizontal, rejected, NAN, meaning));
  data.histograms.push_back(binResiduals("INS fix to trajectory, depth" + sigma_text(survey->config.ins.sigma_depth_m),
                                         "m", depth, rejected, NAN, meaning));
}

}  // namespace hsmap
