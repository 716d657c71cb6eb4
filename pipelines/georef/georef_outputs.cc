#include "pipelines/georef/georef_outputs.h"

#include <fstream>
#include <iomanip>
#include <system_error>

#include "core/io/atomic_file.h"
#include "core/io/ply_io.h"
#include "core/io/results_folder.h"
#include "core/survey/number_text.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"

namespace hsmap {
namespace {

namespace fs = std::filesystem;

constexpr const char* kStaging = "georef.partial";
constexpr const char* kFramesTum = "trajectory/frames.tum";
constexpr const char* kLinesTum = "trajectory/uhi_lines.tum";
constexpr const char* kPoseSources = "trajectory/pose_sources.csv";
constexpr const char* kSummary = "georef/summary.txt";

fs::path prepared(const fs::path& root, const fs::path& relative) {
  const fs::path path = root / relative;
  fs::create_directories(path.parent_path());
  return path;
}

void writeText(const fs::path& path, const std::string& text) {
  AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

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

}  // namespace

std::vector<fs::path> georefProductPaths(const GeorefResult& result) {
  std::vector<fs::path> paths = {results_paths::trajectory_frames, kFramesTum,
                                 results_paths::trajectory_uhi_lines, kLinesTum, kPoseSources,
                                 results_paths::calibration_yaml, kSummary};
  if (!result.landmarks_W.empty()) paths.push_back(results_paths::sparse_ply);
  return paths;
}

void writeGeorefOutputs(const fs::path& run_folder, const GeorefResult& result) {
  const fs::path staging = run_folder / kStaging;
  fs::remove_all(staging);
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
  writeTimedPoseTable(prepared(staging, results_paths::trajectory_frames), frames);
  writeTumTrajectory(prepared(staging, kFramesTum), frames);
  writeLinePoseTable(prepared(staging, results_paths::trajectory_uhi_lines), lines);
  writeTumTrajectory(prepared(staging, kLinesTum), lines_timed);
  writeText(prepared(staging, kPoseSources), poseSourcesCsv(result));

  RunCalibration calibration;
  calibration.variant = result.variant;
  calibration.T_C_U.rotation = result.T_C_U.q;
  calibration.T_C_U.translation_m = result.T_C_U.t;
  calibration.time_offset_s = result.time_offset_s;
  calibration.warnings.push_back("T_C_U and time_offset_s are the survey.yaml guesses: the " +
                                 result.variant + " variant does not estimate them");
  writeRunCalibration(prepared(staging, results_paths::calibration_yaml), calibration);

  if (!result.landmarks_W.empty()) {
    PlyMesh cloud;
    cloud.vertices = result.landmarks_W;
    writePly(prepared(staging, results_paths::sparse_ply), cloud);
  }
  std::string summary = result.summary() + "\n";
  for (const auto& warning : result.warnings) summary += "warning: " + warning + "\n";
  writeText(prepared(staging, kSummary), summary);

  // Everything is complete: move it into place.
  for (const fs::path& relative : georefProductPaths(result)) {
    const fs::path target = prepared(run_folder, relative);
    fs::rename(staging / relative, target);
  }
  std::error_code ignored;
  fs::remove_all(staging, ignored);
}

}  // namespace hsmap
