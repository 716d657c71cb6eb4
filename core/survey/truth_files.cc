#include "core/survey/truth_files.h"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

// Truth files are machine-written: a quaternion further than this from unit
// norm is damage, not rounding (see the header).
constexpr double kQuaternionNormTolerance = 1e-6;
// A few ulps of 1: the squared norm of a normalised quaternion lies within it,
// and such a quaternion is kept bit-exactly.
constexpr double kUnitSquaredNormSlack = 1e-15;

const std::vector<std::string> kPoseColumns = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
const std::vector<std::string> kLinePoseColumns = {"line", "t",  "x",  "y", "z",
                                                   "qw",   "qx", "qy", "qz"};

std::string quaternionNormProblem(const Eigen::Quaterniond& q) {
  const double norm = q.norm();
  if (std::abs(norm - 1.0) <= kQuaternionNormTolerance) return "";
  return "expected a unit quaternion (norm within " + formatDouble(kQuaternionNormTolerance) +
         " of 1), got norm " + formatDouble(norm);
}

// Reads t, x, y, z, qw, qx, qy, qz starting at column `first` of `row`.
void readPose(const CsvTable& table, const CsvTable::Row& row, std::size_t first, double* t,
              SE3d* pose) {
  *t = table.number(row, first);
  const Eigen::Vector3d translation(table.number(row, first + 1), table.number(row, first + 2),
                                    table.number(row, first + 3));
  Eigen::Quaterniond q(table.number(row, first + 4), table.number(row, first + 5),
                       table.number(row, first + 6), table.number(row, first + 7));
  const std::string problem = quaternionNormProblem(q);
  if (!problem.empty()) {
    throw InputError(table.file, InputError::atLine(row.line_number),
                     "columns qw,qx,qy,qz: " + problem);
  }
  if (std::abs(q.squaredNorm() - 1.0) > kUnitSquaredNormSlack) q.normalize();
  *pose = SE3d(q, translation);
}

// Appends ",x,y,z,qw,qx,qy,qz" of `pose` after its time, checking what the reader checks.
void appendPose(std::string* text, const char* writer, double t, const SE3d& pose) {
  const Eigen::Quaterniond& q = pose.q;
  const double values[] = {t, pose.t.x(), pose.t.y(), pose.t.z(), q.w(), q.x(), q.y(), q.z()};
  for (std::size_t i = 0; i < 8; ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument(std::string(writer) + ": non-finite value at time " +
                                  formatDouble(t));
    }
    if (i > 0) *text += ',';
    *text += formatDouble(values[i]);
  }
  const std::string problem = quaternionNormProblem(q);
  if (!problem.empty()) {
    throw std::invalid_argument(std::string(writer) + ": pose at time " + formatDouble(t) + ": " +
                                problem);
  }
  *text += '\n';
}

void requireIncreasingTime(const char* writer, std::size_t index, double previous_t, double t) {
  if (index > 0 && !(t > previous_t)) {
    throw std::invalid_argument(std::string(writer) + ": times must be strictly increasing, got " +
                                formatDouble(t) + " after " + formatDouble(previous_t));
  }
}

void writeAtomically(const std::filesystem::path& file, const std::string& text) {
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

// ---- calibration.yaml ------------------------------------------------------

std::vector<double> readAttenuation(const StrictYamlMap& root, const YAML::Node& document) {
  const std::string key = "water_attenuation_per_m";
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
                            "uhi_camera", "water_attenuation_per_m"});
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
  calibration.water_attenuation_per_m = readAttenuation(root, document);
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
  out << YAML::EndMap;
  if (!out.good()) {
    throw std::logic_error("writeTruthCalibration: YAML emitter: " + out.GetLastError());
  }
  return std::string(out.c_str()) + "\n";
}

}  // namespace

// ---- rgb_poses.csv -----------------------------------------------------------

std::vector<TruthPose> readTruthPoses(const std::filesystem::path& file) {
  const CsvTable table = readCsvTable(file, {kPoseColumns});
  std::vector<TruthPose> poses;
  poses.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    TruthPose pose;
    readPose(table, row, 0, &pose.t, &pose.T_W_X);
    if (!poses.empty()) checkTimeOrder(table, row, 0, poses.back().t, pose.t);
    poses.push_back(pose);
  }
  return poses;
}

void writeTruthPoses(const std::filesystem::path& file, const std::vector<TruthPose>& poses) {
  const char* writer = "writeTruthPoses";
  if (poses.empty()) throw std::invalid_argument("writeTruthPoses: expected at least one pose");
  std::string text = "t,x,y,z,qw,qx,qy,qz\n";
  for (std::size_t i = 0; i < poses.size(); ++i) {
    requireIncreasingTime(writer, i, i > 0 ? poses[i - 1].t : 0.0, poses[i].t);
    appendPose(&text, writer, poses[i].t, poses[i].T_W_X);
  }
  writeAtomically(file, text);
}

// ---- uhi_poses.csv -----------------------------------------------------------

std::vector<TruthLinePose> readTruthLinePoses(const std::filesystem::path& file) {
  const CsvTable table = readCsvTable(file, {kLinePoseColumns});
  std::vector<TruthLinePose> poses;
  poses.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    TruthLinePose pose;
    const long long expected = static_cast<long long>(poses.size());
    pose.line = table.integer(row, 0);
    if (pose.line != expected) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'line': expected scan line " + std::to_string(expected) +
                           " (one row per scan line, counting from 0 in order), got " +
                           std::to_string(pose.line));
    }
    readPose(table, row, 1, &pose.t, &pose.T_W_U);
    if (!poses.empty()) checkTimeOrder(table, row, 1, poses.back().t, pose.t);
    poses.push_back(pose);
  }
  return poses;
}

void writeTruthLinePoses(const std::filesystem::path& file,
                         const std::vector<TruthLinePose>& poses) {
  const char* writer = "writeTruthLinePoses";
  if (poses.empty()) {
    throw std::invalid_argument("writeTruthLinePoses: expected at least one scan line");
  }
  std::string text = "line,t,x,y,z,qw,qx,qy,qz\n";
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (poses[i].line != static_cast<long long>(i)) {
      throw std::invalid_argument("writeTruthLinePoses: expected scan line " + std::to_string(i) +
                                  " at position " + std::to_string(i) + ", got " +
                                  std::to_string(poses[i].line));
    }
    requireIncreasingTime(writer, i, i > 0 ? poses[i - 1].t : 0.0, poses[i].t);
    text += std::to_string(poses[i].line) + ',';
    appendPose(&text, writer, poses[i].t, poses[i].T_W_U);
  }
  writeAtomically(file, text);
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
