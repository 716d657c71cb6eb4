#include "pipelines/report/collect_trajectory.h"

#include <cmath>

#include "core/io/results_folder.h"
#include "core/survey/ins_fixes_in_world.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "pipelines/report/named_csv.h"

namespace hsmap {

namespace fs = std::filesystem;

fs::path adjustedMapFolder(const fs::path& run, const std::string& variant) {
  std::error_code error;
  if (variant == "joint" && fs::is_directory(run / "joint", error)) return run / "joint";
  return run / "georef";
}

void collectTrajectory(const fs::path& run, const Survey* survey, ReportData& data) {
  std::error_code error;
  const fs::path frames_csv = run / results_paths::trajectory_frames;
  if (fs::is_regular_file(frames_csv, error)) {
    for (const TimedPose& pose : readTimedPoseTable(frames_csv)) {
      const Eigen::Vector3d& p = pose.T.t;
      data.frames.push_back({pose.t, p.x(), p.y(), p.z()});
    }
  } else {
    data.notes.push_back("no trajectory: " + frames_csv.string() + " is missing");
  }

  const fs::path keyframes_csv = adjustedMapFolder(run, data.variant) / "keyframes.csv";
  if (fs::is_regular_file(keyframes_csv, error)) {
    const NamedCsv keyframes(keyframes_csv, {"t", "x", "y", "z"});
    for (std::size_t row = 0; row < keyframes.rowCount(); ++row) {
      data.keyframes.push_back({keyframes.number(row, "t"), keyframes.number(row, "x"), keyframes.number(row, "y"),
                                keyframes.number(row, "z")});
    }
  } else {
    data.notes.push_back("no keyframes: " + keyframes_csv.string() + " is missing (the " + data.variant +
                         " variant has no visual map, or the run stopped before geo-referencing)");
  }

  if (survey != nullptr) {
    const fs::path rejected_csv = run / "georef" / "rejected_fixes.csv";
    std::vector<std::pair<long long, std::string>> rejected;  // ins.csv line, step
    if (fs::is_regular_file(rejected_csv, error)) {
      const NamedCsv table(rejected_csv, {"ins_line", "step"});
      for (std::size_t row = 0; row < table.rowCount(); ++row) {
        rejected.emplace_back(table.integer(row, "ins_line"), table.text(row, "step"));
      }
    }
    for (const InsFixInWorld& fix : insFixesInWorld(*survey)) {
      ReportInsFix shown;
      shown.position = {fix.t, fix.p_W_B.x(), fix.p_W_B.y(), fix.p_W_B.z()};
      shown.ins_line = fix.line_number;
      for (const auto& [line, step] : rejected) {
        if (line == fix.line_number) {
          shown.rejected = true;
          shown.rejected_at = step;
        }
      }
      data.ins_fixes.push_back(shown);
    }
  }

  const fs::path losses_csv = run / "frontend" / "losses.csv";
  if (fs::is_regular_file(losses_csv, error)) {
    const NamedCsv losses(losses_csv, {"first_frame", "last_frame", "reason"});
    for (std::size_t row = 0; row < losses.rowCount(); ++row) {
      ReportTrackingLoss loss;
      loss.first_frame = losses.integer(row, "first_frame");
      loss.last_frame = losses.integer(row, "last_frame");
      loss.reason = losses.text(row, "reason");
      const auto time_of = [&](long long frame) {
        return frame >= 0 && std::size_t(frame) < data.frames.size() ? data.frames[std::size_t(frame)].t : NAN;
      };
      loss.t_first = time_of(loss.first_frame);
      loss.t_last = time_of(loss.last_frame);
      data.losses.push_back(loss);
    }
  }
}

}  // namespace hsmap
