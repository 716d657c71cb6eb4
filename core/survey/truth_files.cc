#include "core/survey/truth_files.h"

#include <optional>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"
#include "core/survey/pose_tables.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

void writeAtomically(const std::filesystem::path& file, const std::string& text) {
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

// ---- calibration.yaml ------------------------------------------------------

// A non-empty list of numbers >= 0, one per UHI band, at `key`.
std::vector<double> readPerBandList(const StrictYamlMap& root, const YAML::Node& document, const std::string& key) {
  if (!root.has(key)) root.fail(key, "missing required key");
  const YAML::Node list = document[key];
  const std::string expected = "expected a non-empty list of numbers >= 0 (one per UHI band)";
  if (!list.IsSequence()) root.fail(key, expected + ", got " + describeYamlNode(list));
  if (list.size() == 0) root.fail(key, expected + ", got an empty list");
  std::vector<double> values;
  values.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node element = list[i];
    const YAML::Mark mark = element.Mark();
    const long long line = mark.is_null() ? root.lineOf(key) : mark.line + 1;
    const std::string where = InputError::atLine(line) + ", " +
                              InputError::atKey(key + "[" + std::to_string(i) + "]");
    std::string message = "expected a number, got " + describeYamlNode(element);
    std::optional<double> value;
    if (element.IsScalar()) value = parseFiniteDouble(element.Scalar(), &message);
    if (!value) throw InputError(root.file(), where, message);
    if (*value < 0.0) {
      throw InputError(root.file(), where, "expected a number >= 0, got " + formatDouble(*value));
    }
    values.push_back(*value);
  }
  return values;
}

TruthCalibration parseTruthCalibration(const std::filesystem::path& file,
                                       const YAML::Node& document) {
  if (document.IsNull()) {
    throw InputError(file, InputError::atLine(1),
                     std::string("empty file; expected a YAML map starting with 'format: ") +
                         TruthCalibration::kFormat + "'");
  }
  const StrictYamlMap root(file, document, "", 1,
                           {"format", "T_C_U", "time_offset_s", "T_B_C", "rgb_camera",
                            "uhi_camera", "water_attenuation_per_m", "backscatter_dn"});
  const std::string format = root.text("format");
  if (format != TruthCalibration::kFormat) {
    root.fail("format", "unsupported format " + quoteForMessage(format) + "; expected '" +
                            TruthCalibration::kFormat + "'");
  }
  TruthCalibration calibration;
  calibration.T_C_U = readRigidTransform(root.map("T_C_U", {"rotation_wxyz", "translation_m"}));
  calibration.time_offset_s = root.number("time_offset_s");
  calibration.T_B_C = readRigidTransform(root.map("T_B_C", {"rotation_wxyz", "translation_m"}));
  calibration.rgb_camera = readPinholeRadtanCamera(root, "rgb_camera");
  calibration.uhi_camera = readPushbroomCamera(root, "uhi_camera");
  calibration.water_attenuation_per_m = readPerBandList(root, document, "water_attenuation_per_m");
  if (root.has("backscatter_dn")) {
    calibration.backscatter_dn = readPerBandList(root, document, "backscatter_dn");
    if (calibration.backscatter_dn.size() != calibration.water_attenuation_per_m.size()) {
      root.fail("backscatter_dn", "expected " + std::to_string(calibration.water_attenuation_per_m.size()) +
                                      " numbers (one per UHI band, as water_attenuation_per_m), got " +
                                      std::to_string(calibration.backscatter_dn.size()));
    }
  }
  return calibration;
}

std::string emitTruthCalibration(const TruthCalibration& calibration) {
  YAML::Emitter out;
  out << YAML::Comment("hsmap ground-truth calibration (format: see docs/SURVEY_FORMAT.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << TruthCalibration::kFormat;
  out << YAML::Key << "T_C_U" << YAML::Value << YAML::Flow << YAML::BeginMap;
  emitRigidTransformKeys(out, calibration.T_C_U);
  out << YAML::EndMap;
  out << YAML::Key << "time_offset_s" << YAML::Value;
  emitNumber(out, calibration.time_offset_s);
  out << YAML::Key << "T_B_C" << YAML::Value << YAML::Flow << YAML::BeginMap;
  emitRigidTransformKeys(out, calibration.T_B_C);
  out << YAML::EndMap;
  out << YAML::Key << "rgb_camera" << YAML::Value;
  emitPinholeRadtanCamera(out, calibration.rgb_camera);
  out << YAML::Key << "uhi_camera" << YAML::Value;
  emitPushbroomCamera(out, calibration.uhi_camera);
  out << YAML::Key << "water_attenuation_per_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double c : calibration.water_attenuation_per_m) emitNumber(out, c);
  out << YAML::EndSeq;
  if (!calibration.backscatter_dn.empty()) {
    out << YAML::Key << "backscatter_dn" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double b : calibration.backscatter_dn) emitNumber(out, b);
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  if (!out.good()) {
    throw std::logic_error("writeTruthCalibration: YAML emitter: " + out.GetLastError());
  }
  return std::string(out.c_str()) + "\n";
}

}  // namespace

// ---- rgb_poses.csv, uhi_poses.csv: the pose tables of pose_tables.h --------

std::vector<TruthPose> readTruthPoses(const std::filesystem::path& file) {
  const std::vector<TimedPose> table = readTimedPoseTable(file);
  std::vector<TruthPose> poses;
  poses.reserve(table.size());
  for (const TimedPose& pose : table) poses.push_back({pose.t, pose.T});
  return poses;
}

void writeTruthPoses(const std::filesystem::path& file, const std::vector<TruthPose>& poses) {
  std::vector<TimedPose> table;
  table.reserve(poses.size());
  for (const TruthPose& pose : poses) table.push_back({pose.t, pose.T_W_X});
  writeTimedPoseTable(file, table, "writeTruthPoses");
}

std::vector<TruthLinePose> readTruthLinePoses(const std::filesystem::path& file) {
  const std::vector<LinePose> table = readLinePoseTable(file);
  std::vector<TruthLinePose> poses;
  poses.reserve(table.size());
  for (const LinePose& pose : table) poses.push_back({pose.line, pose.t, pose.T});
  return poses;
}

void writeTruthLinePoses(const std::filesystem::path& file,
                         const std::vector<TruthLinePose>& poses) {
  std::vector<LinePose> table;
  table.reserve(poses.size());
  for (const TruthLinePose& pose : poses) table.push_back({pose.line, pose.t, pose.T_W_U});
  writeLinePoseTable(file, table, "writeTruthLinePoses");
}

// ---- calibration.yaml --------------------------------------------------------

TruthCalibration readTruthCalibration(const std::filesystem::path& file) {
  return parseTruthCalibration(file, loadYamlFile(file));
}

void writeTruthCalibration(const std::filesystem::path& file,
                           const TruthCalibration& calibration) {
  const std::string text = emitTruthCalibration(calibration);
  // Run the reader's checks on the text before it reaches the disk, so hsmap
  // never writes a calibration.yaml that it would itself refuse.
  try {
    parseTruthCalibration(file, YAML::Load(text));
  } catch (const InputError& e) {
    throw std::invalid_argument(std::string("writeTruthCalibration: invalid calibration: ") +
                                e.what());
  }
  writeAtomically(file, text);
}

}  // namespace hsmap
