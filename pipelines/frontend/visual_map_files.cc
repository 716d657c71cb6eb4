#include "pipelines/frontend/visual_map_files.h"

#include <sstream>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "pipelines/frontend/csv_cells.h"

namespace hsmap {

namespace {

namespace fs = std::filesystem;
using namespace csv_cells;

const std::vector<std::string> kKeyframesHeader{"keyframe", "frame", "t",  "segment", "x", "y",
                                                "z",        "qw",    "qx", "qy",      "qz"};
const std::vector<std::string> kObservationsHeader{"keyframe", "landmark", "u", "v"};
const std::vector<std::string> kLandmarksHeader{"landmark", "x", "y", "z", "observations", "keyframes"};

}  // namespace

void writeVisualMapFiles(const fs::path& folder, const VisualMap& map) {
  std::ostringstream keyframes, observations, landmarks;
  keyframes << header(kKeyframesHeader);
  observations << header(kObservationsHeader);
  for (const Keyframe& k : map.keyframes()) {
    keyframes << k.id << "," << k.frame_index << "," << number(k.t) << "," << k.segment << ","
              << pose(k.T_F_C) << "\n";
    for (const auto& o : k.observations) {
      observations << k.id << "," << o.landmark_id << "," << number(o.pixel.x()) << ","
                   << number(o.pixel.y()) << "\n";
    }
  }
  landmarks << header(kLandmarksHeader);
  for (const Landmark& l : map.landmarks()) {
    if (!l.valid) continue;
    landmarks << l.id << "," << number(l.p_F.x()) << "," << number(l.p_F.y()) << ","
              << number(l.p_F.z()) << "," << l.keyframe_ids.size() << ",";
    for (std::size_t i = 0; i < l.keyframe_ids.size(); ++i) landmarks << (i ? " " : "") << l.keyframe_ids[i];
    landmarks << "\n";
  }
  writeFile(folder / visual_map_files::keyframes, keyframes.str());
  writeFile(folder / visual_map_files::observations, observations.str());
  writeFile(folder / visual_map_files::landmarks, landmarks.str());

}

VisualMap readVisualMapFiles(const fs::path& folder) {
  // Keyframes, then landmarks, then the observations that tie them.
  const CsvTable keyframe_table = readCsvTable(folder / visual_map_files::keyframes, {kKeyframesHeader});
  std::vector<Keyframe> keyframes;
  for (const auto& row : keyframe_table.rows) {
    Keyframe k;
    k.id = id(keyframe_table, row, 0);
    if (k.id != int(keyframes.size())) bad(keyframe_table, row, "keyframe ids must count 0, 1, 2, ...");
    k.frame_index = id(keyframe_table, row, 1);
    k.t = keyframe_table.number(row, 2);
    k.segment = id(keyframe_table, row, 3);
    k.T_F_C = readPose(keyframe_table, row, 4);
    keyframes.push_back(std::move(k));
  }
  const CsvTable landmark_table = readCsvTable(folder / visual_map_files::landmarks, {kLandmarksHeader});
  std::vector<Landmark> landmarks;
  for (const auto& row : landmark_table.rows) {
    const int l = id(landmark_table, row, 0);
    if (l < int(landmarks.size())) bad(landmark_table, row, "landmark ids must increase");
    while (int(landmarks.size()) < l) {  // ids of removed landmarks: empty slots
      Landmark gap;
      gap.id = int(landmarks.size());
      gap.valid = false;
      landmarks.push_back(gap);
    }
    Landmark landmark;
    landmark.id = l;
    landmark.p_F = {landmark_table.number(row, 1), landmark_table.number(row, 2),
                    landmark_table.number(row, 3)};
    landmarks.push_back(landmark);
  }
  const CsvTable observation_table =
      readCsvTable(folder / visual_map_files::observations, {kObservationsHeader});
  for (const auto& row : observation_table.rows) {
    const int k = id(observation_table, row, 0);
    const int l = id(observation_table, row, 1);
    if (k < 0 || k >= int(keyframes.size())) bad(observation_table, row, "unknown keyframe " + std::to_string(k));
    if (l < 0 || l >= int(landmarks.size()) || !landmarks[std::size_t(l)].valid) {
      bad(observation_table, row, "unknown landmark " + std::to_string(l));
    }
    keyframes[std::size_t(k)].observations.push_back(
        {l, Eigen::Vector2d(observation_table.number(row, 2), observation_table.number(row, 3))});
    landmarks[std::size_t(l)].keyframe_ids.push_back(k);
  }
  for (const auto& row : landmark_table.rows) {
    const Landmark& landmark = landmarks[std::size_t(id(landmark_table, row, 0))];
    if (int(landmark.keyframe_ids.size()) != id(landmark_table, row, 4)) {
      bad(landmark_table, row, "column 'observations' does not match observations.csv");
    }
  }
  VisualMap map;
  map.assign(std::move(keyframes), std::move(landmarks));
  return map;
}

}  // namespace hsmap
