#include "core/survey/run_calibration.h"

#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/camera_sigma.h"
#include "core/survey/results_yaml.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

// Same bounds as survey.yaml (survey_config.h, calibration_yaml.cc): an hour
// either way for d, 1e6 px for a focal length or centre.
constexpr double kMaxFocalPx = 1e6;
constexpr double kMaxTimeOffsetS = 3600.0;

RunCalibration parseDocument(const std::filesystem::path& file, const YAML::Node& document) {
  if (document.IsNull()) {
    throw InputError(file, InputError::atLine(1),
                     std::string("empty file; expected a YAML map starting with 'format: ") +
                         RunCalibration::kFormat + "'");
  }
  const StrictYamlMap root(file, document, "", 1,
                           {"format", "variant", "T_C_U", "time_offset_s", "time_offset_sigma_s",
                            "uhi_camera", "rgb_camera", "water", "warnings"});
  const std::string format = root.text("format");
  if (format != RunCalibration::kFormat) {
    root.fail("format", "unsupported format " + quoteForMessage(format) + "; expected '" +
                            RunCalibration::kFormat + "'");
  }
  RunCalibration calibration;
  calibration.variant = readRunVariant(root, "variant");
  const StrictYamlMap extrinsic = root.map(
      "T_C_U", {"rotation_wxyz", "translation_m", "sigma_rotation_deg", "sigma_translation_m"});
  calibration.T_C_U = readRigidTransform(extrinsic);
  const YAML::Node extrinsic_node = document["T_C_U"];
  calibration.sigma_rotation_deg =
      readNullableSigmas(extrinsic, extrinsic_node["sigma_rotation_deg"], "sigma_rotation_deg");
  calibration.sigma_translation_m =
      readNullableSigmas(extrinsic, extrinsic_node["sigma_translation_m"], "sigma_translation_m");
  calibration.time_offset_s =
      root.numberInRange("time_offset_s", -kMaxTimeOffsetS, kMaxTimeOffsetS);
  calibration.time_offset_sigma_s =
      readNullableSigma(root, document["time_offset_sigma_s"], "time_offset_sigma_s");
  if (root.has("uhi_camera")) {
    const StrictYamlMap camera = root.map("uhi_camera", {"f", "cx", "distortion", "sigma"});
    UhiCameraEstimate estimate;
    estimate.f = camera.positiveNumberUpTo("f", kMaxFocalPx);
    estimate.cx = camera.numberInRange("cx", -kMaxFocalPx, kMaxFocalPx);
    const std::vector<double> distortion = camera.numbers("distortion", 2);
    estimate.distortion = {distortion[0], distortion[1]};
    estimate.sigma = readPushbroomSigma(camera, "sigma");
    calibration.uhi_camera = estimate;
  }
  if (root.has("rgb_camera")) {
    const StrictYamlMap camera = root.map("rgb_camera", {"fx", "fy", "cx", "cy", "distortion", "sigma"});
    RgbCameraEstimate estimate;
    estimate.fx = camera.positiveNumberUpTo("fx", kMaxFocalPx);
    estimate.fy = camera.positiveNumberUpTo("fy", kMaxFocalPx);
    estimate.cx = camera.numberInRange("cx", -kMaxFocalPx, kMaxFocalPx);
    estimate.cy = camera.numberInRange("cy", -kMaxFocalPx, kMaxFocalPx);
    const std::vector<double> distortion = camera.numbers("distortion", 5);
    for (std::size_t i = 0; i < 5; ++i) estimate.distortion[i] = distortion[i];
    estimate.sigma = readPinholeRadtanSigma(camera, "sigma");
    calibration.rgb_camera = estimate;
  }
  if (root.has("water")) calibration.water = readWaterBlock(file, document["water"], "water");
  calibration.warnings = readTextList(root, document["warnings"], "warnings");
  return calibration;
}

void emitSigmas(YAML::Emitter& out, const std::optional<Eigen::Vector3d>& sigmas) {
  if (!sigmas) {
    out << YAML::Null;
    return;
  }
  out << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < 3; ++i) emitNumber(out, (*sigmas)[i]);
  out << YAML::EndSeq;
}

std::string emitDocument(const RunCalibration& calibration) {
  YAML::Emitter out;
  out.SetNullFormat(YAML::LowerNull);  // `null`, as the contract writes it (not `~`)
  out << YAML::Comment("hsmap run calibration (format: see docs/EVALUATE.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << RunCalibration::kFormat;
  out << YAML::Key << "variant" << YAML::Value << calibration.variant;
  out << YAML::Key << "T_C_U" << YAML::Value << YAML::BeginMap;
  emitRigidTransformKeys(out, calibration.T_C_U);
  out << YAML::Key << "sigma_rotation_deg" << YAML::Value;
  emitSigmas(out, calibration.sigma_rotation_deg);
  out << YAML::Key << "sigma_translation_m" << YAML::Value;
  emitSigmas(out, calibration.sigma_translation_m);
  out << YAML::EndMap;
  out << YAML::Key << "time_offset_s" << YAML::Value;
  emitNumber(out, calibration.time_offset_s);
  out << YAML::Key << "time_offset_sigma_s" << YAML::Value;
  if (calibration.time_offset_sigma_s) {
    emitNumber(out, *calibration.time_offset_sigma_s);
  } else {
    out << YAML::Null;
  }
  if (calibration.uhi_camera) {
    const UhiCameraEstimate& camera = *calibration.uhi_camera;
    out << YAML::Key << "uhi_camera" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "f" << YAML::Value;
    emitNumber(out, camera.f);
    out << YAML::Key << "cx" << YAML::Value;
    emitNumber(out, camera.cx);
    out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double k : camera.distortion) emitNumber(out, k);
    out << YAML::EndSeq;
    out << YAML::Key << "sigma" << YAML::Value;
    emitPushbroomSigma(out, camera.sigma);
    out << YAML::EndMap;
  }
  if (calibration.rgb_camera) {
    const RgbCameraEstimate& camera = *calibration.rgb_camera;
    out << YAML::Key << "rgb_camera" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const auto& [key, value] : {std::pair<const char*, double>{"fx", camera.fx}, {"fy", camera.fy},
                                     {"cx", camera.cx}, {"cy", camera.cy}}) {
      out << YAML::Key << key << YAML::Value;
      emitNumber(out, value);
    }
    out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double k : camera.distortion) emitNumber(out, k);
    out << YAML::EndSeq;
    out << YAML::Key << "sigma" << YAML::Value;
    emitPinholeRadtanSigma(out, camera.sigma);
    out << YAML::EndMap;
  }
  if (calibration.water) {
    out << YAML::Key << "water" << YAML::Value;
    emitWaterBlock(out, *calibration.water);
  }
  out << YAML::Key << "warnings" << YAML::Value;
  if (calibration.warnings.empty()) {
    out << YAML::Flow;  // `warnings: []`
  }
  out << YAML::BeginSeq;
  for (const std::string& warning : calibration.warnings) out << YAML::DoubleQuoted << warning;
  out << YAML::EndSeq;
  out << YAML::EndMap;
  if (!out.good()) {
    throw std::logic_error("writeRunCalibration: YAML emitter: " + out.GetLastError());
  }
  return std::string(out.c_str()) + "\n";
}

}  // namespace

PushbroomParameters UhiCameraEstimate::appliedTo(PushbroomParameters survey_camera) const {
  survey_camera.f = f;
  survey_camera.cx = cx;
  survey_camera.distortion = distortion;
  return survey_camera;
}

PinholeRadtanParameters RgbCameraEstimate::appliedTo(PinholeRadtanParameters survey_camera) const {
  survey_camera.fx = fx;
  survey_camera.fy = fy;
  survey_camera.cx = cx;
  survey_camera.cy = cy;
  survey_camera.distortion = distortion;
  return survey_camera;
}

RunCalibration parseRunCalibration(std::string_view text, const std::filesystem::path& file) {
  return parseDocument(file, parseYamlText(text, file));
}

RunCalibration readRunCalibration(const std::filesystem::path& file) {
  return parseDocument(file, loadYamlFile(file));
}

void writeRunCalibration(const std::filesystem::path& file, const RunCalibration& calibration) {
  const std::string text = emitDocument(calibration);
  // The reader's checks on the text before it reaches the disk: hsmap never
  // writes a calibration.yaml that it would itself refuse.
  try {
    parseRunCalibration(text, file);
  } catch (const InputError& e) {
    throw std::invalid_argument(std::string("writeRunCalibration: invalid calibration: ") +
                                e.what());
  }
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

}  // namespace hsmap
