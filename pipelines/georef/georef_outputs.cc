#include "pipelines/georef/georef_outputs.h"

#include <map>
#include <system_error>

#include "core/io/atomic_file.h"
#include "core/io/ply_io.h"
#include "core/io/results_folder.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/survey/pose_tables.h"
#include "core/util/input_error.h"
#include "pipelines/frontend/visual_map_files.h"

namespace hsmap {
namespace {

namespace fs = std::filesystem;

std::string poseSourcesCsv(const GeorefResult& result) {
  std::string text = "kind,index,t,source\n";
  for (const auto& f : result.frames) {
    text += "frame," + std::to_string(f.index) + "," + formatDouble(f.t) + "," + toString(f.source) + "\n";
  }
  for (const auto& l : result.lines) {
    text += "line," + std::to_string(l.line) + "," + formatDouble(l.t) + "," + toString(l.source) + "\n";
  }
  return text;
}

std::string rejectedFixesCsv(const GeorefResult& result) {
  std::string text = "fix,ins_line,t,offset_m,step\n";
  for (const RejectedFix& fix : result.rejected_fixes) {
    text += std::to_string(fix.fix) + "," + std::to_string(fix.line_number) + "," + formatDouble(fix.t) + "," +
            formatDouble(fix.offset_m) + "," + fix.stage + "\n";
  }
  return text;
}

PoseSource poseSource(const CsvTable& table, const CsvTable::Row& row, std::size_t column) {
  const std::string& text = row.cells[column];
  for (PoseSource source : {PoseSource::vision, PoseSource::ins_bridged, PoseSource::ins_only, PoseSource::held}) {
    if (text == toString(source)) return source;
  }
  throw InputError(table.file, InputError::atLine(row.line_number),
                   "column 'source': expected vision, ins_bridged, ins_only or held, got '" + text + "'");
}

}  // namespace

std::vector<std::string> rgbCameraWarnings(const GeorefResult& result) {
  std::vector<std::string> warnings;
  if (!result.rgb_camera) return warnings;
  warnings.push_back(
      "rgb_camera estimated by the geo-referencing bundle adjustment (survey.yaml's rgb.camera_sigma); the "
      "later stages use it");
  if (!result.rgb_camera->sigma_known) {
    warnings.push_back("rgb_camera: no covariance (" + result.rgb_camera->covariance_error +
                       "): its sigmas are written as 0");
  }
  for (const std::string& warning : result.rgb_camera->inseparable) warnings.push_back(warning);
  return warnings;
}

void carryRgbCamera(const RunCalibration& from, RunCalibration& to) {
  to.rgb_camera = from.rgb_camera;
  std::erase_if(to.warnings, [](const std::string& warning) { return warning.starts_with("rgb_camera"); });
  for (const std::string& warning : from.warnings) {
    if (warning.starts_with("rgb_camera")) to.warnings.push_back(warning);
  }
}

RunCalibration georefCalibration(const GeorefResult& result, std::vector<std::string> warnings) {
  RunCalibration calibration;
  calibration.variant = result.variant;
  calibration.T_C_U.rotation = result.T_C_U.q;
  calibration.T_C_U.translation_m = result.T_C_U.t;
  calibration.time_offset_s = result.time_offset_s;
  if (result.rgb_camera) {
    const RgbIntrinsicsEstimate& estimate = *result.rgb_camera;
    RgbCameraEstimate camera;
    camera.fx = estimate.camera.fx;
    camera.fy = estimate.camera.fy;
    camera.cx = estimate.camera.cx;
    camera.cy = estimate.camera.cy;
    camera.distortion = estimate.camera.distortion;
    camera.sigma.fx = estimate.sigma[0];
    camera.sigma.fy = estimate.sigma[1];
    camera.sigma.cx = estimate.sigma[2];
    camera.sigma.cy = estimate.sigma[3];
    for (std::size_t i = 0; i < 5; ++i) camera.sigma.distortion[i] = estimate.sigma[4 + i];
    calibration.rgb_camera = camera;
  }
  if (warnings.empty()) {
    warnings.push_back("T_C_U and time_offset_s are the survey.yaml guesses: the " + result.variant +
                       " variant does not estimate them");
  }
  if (result.placement) {
    if (const std::string scale = scaleWarning(*result.placement); !scale.empty()) warnings.push_back(scale);
  }
  for (const std::string& warning : rgbCameraWarnings(result)) warnings.push_back(warning);
  calibration.warnings = std::move(warnings);
  return calibration;
}

void writeGeorefOutputs(const fs::path& folder, const GeorefResult& result) {
  writeGeorefOutputs(folder, result, georefCalibration(result));
}

void writeGeorefOutputs(const fs::path& folder, const GeorefResult& result, const RunCalibration& calibration) {
  const fs::path staging = AtomicFile::partialPathFor(folder);
  fs::remove_all(staging);
  fs::create_directories(staging);
  std::vector<TimedPose> frames;
  frames.reserve(result.frames.size());
  for (const auto& f : result.frames) frames.push_back({f.t, f.T_W_C});
  std::vector<LinePose> lines;
  std::vector<TimedPose> lines_timed;
  lines.reserve(result.lines.size());
  for (const auto& l : result.lines) {
    lines.push_back({l.line, l.t, l.T_W_U});
    lines_timed.push_back({l.t, l.T_W_U});
  }
  writeTimedPoseTable(staging / georef_files::frames, frames);
  writeTumTrajectory(staging / georef_files::frames_tum, frames);
  writeLinePoseTable(staging / georef_files::lines, lines);
  writeTumTrajectory(staging / georef_files::lines_tum, lines_timed);
  writeTextAtomically(staging / georef_files::pose_sources, poseSourcesCsv(result));
  // Tables with no row are not written (the CSV rules refuse them): a
  // missing file reads as none.
  if (!result.rejected_fixes.empty()) {
    writeTextAtomically(staging / georef_files::rejected_fixes, rejectedFixesCsv(result));
  }
  writeRunCalibration(staging / georef_files::calibration, calibration);
  if (!result.map_W.keyframes().empty()) writeVisualMapFiles(staging, result.map_W);
  if (!result.landmarks_W.empty()) {
    PlyMesh cloud;
    cloud.vertices = result.landmarks_W;
    writePly(staging / georef_files::sparse_ply, cloud);
  }
  if (result.placement) writeMapPlacement(staging / georef_files::map_placement, *result.placement);
  std::string summary = result.summary() + "\n";
  for (const auto& warning : result.warnings) summary += "warning: " + warning + "\n";
  writeTextAtomically(staging / georef_files::summary, summary);

  // Everything is complete: move it into place.
  fs::remove_all(folder);
  fs::rename(staging, folder);
}

GeorefResult readGeorefOutputs(const fs::path& folder) {
  GeorefResult result;
  const RunCalibration calibration = readRunCalibration(folder / georef_files::calibration);
  result.variant = calibration.variant;
  result.T_C_U = SE3d(calibration.T_C_U.rotation, calibration.T_C_U.translation_m);
  result.time_offset_s = calibration.time_offset_s;
  if (calibration.rgb_camera) {
    const RgbCameraEstimate& camera = *calibration.rgb_camera;
    RgbIntrinsicsEstimate estimate;
    // model, width and height are survey.yaml's (RgbCameraEstimate::appliedTo).
    estimate.camera.fx = camera.fx;
    estimate.camera.fy = camera.fy;
    estimate.camera.cx = camera.cx;
    estimate.camera.cy = camera.cy;
    estimate.camera.distortion = camera.distortion;
    estimate.sigma = rgbIntrinsicsOf(camera.sigma);
    estimate.sigma_known = true;
    result.rgb_camera = estimate;
  }

  const std::vector<TimedPose> frames = readTimedPoseTable(folder / georef_files::frames);
  const std::vector<LinePose> lines = readLinePoseTable(folder / georef_files::lines);
  const CsvTable sources = readCsvTable(folder / georef_files::pose_sources, {{"kind", "index", "t", "source"}});
  std::size_t frame = 0, line = 0;
  for (const auto& row : sources.rows) {
    const std::string& kind = row.cells[0];
    const long long index = sources.integer(row, 1);
    const PoseSource source = poseSource(sources, row, 3);
    if (kind == "frame" && frame < frames.size()) {
      result.frames.push_back({int(index), frames[frame].t, frames[frame].T, source});
      ++frame;
    } else if (kind == "line" && line < lines.size() && lines[line].line == index) {
      result.lines.push_back({lines[line].line, lines[line].t, lines[line].T, source});
      ++line;
    } else {
      throw InputError(sources.file, InputError::atLine(row.line_number),
                       std::string("expected the rows of ") + georef_files::frames + " then of " +
                           georef_files::lines + ", in their order, got '" + kind + "' " + std::to_string(index));
    }
  }
  if (frame != frames.size() || line != lines.size()) {
    throw InputError(sources.file, "", "expected a row for each of the " + std::to_string(frames.size()) +
                                       " frames and " + std::to_string(lines.size()) + " scan lines, got " +
                                       std::to_string(frame) + " and " + std::to_string(line));
  }
  if (fs::exists(folder / georef_files::rejected_fixes)) {
    const CsvTable rejected =
        readCsvTable(folder / georef_files::rejected_fixes, {{"fix", "ins_line", "t", "offset_m", "step"}});
    for (const auto& row : rejected.rows) {
      result.rejected_fixes.push_back({int(rejected.integer(row, 0)), rejected.integer(row, 1),
                                       rejected.number(row, 2), rejected.number(row, 3), row.cells[4]});
    }
  }
  if (fs::exists(folder / visual_map_files::keyframes)) result.map_W = readVisualMapFiles(folder);
  if (fs::exists(folder / georef_files::map_placement)) {
    result.placement = readMapPlacement(folder / georef_files::map_placement);
  }
  for (const Landmark& landmark : result.map_W.landmarks()) {
    if (landmark.valid) result.landmarks_W.push_back(landmark.p_F);
  }
  return result;
}

}  // namespace hsmap
