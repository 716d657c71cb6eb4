#include "core/survey/survey_config.h"

#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

// Physical bounds of the survey's numbers (survey_config.h): finite is not
// enough (a time of 1e300 or a depth of 1e308 passes a finiteness check).
constexpr double kMaxAbsTimeS = 4e9;            // as in the CSV tables
constexpr double kMaxFrameRateHz = 10000.0;
constexpr double kMaxAbsTimeOffsetS = 3600.0;   // UHI clock vs the shared clock
constexpr double kMaxTimeSigmaS = 3600.0;
constexpr double kMaxRotationSigmaDeg = 180.0;
constexpr double kMaxTranslationSigmaM = 100.0;
constexpr double kMaxPositionSigmaM = 10000.0;
constexpr double kMinDepthM = -10000.0, kMaxDepthM = 12000.0;

// Remembers the line of a key that names a file, so that loadSurvey can
// report a missing or non-regular file at the survey.yaml key that named it.
void rememberFileKey(SurveyConfig& config, const StrictYamlMap& map, const std::string& key) {
  if (map.has(key)) config.file_key_lines[map.keyPath(key)] = map.lineOf(key);
}

RgbConfig parseRgb(const StrictYamlMap& root, SurveyConfig& survey) {
  const StrictYamlMap rgb =
      root.map("rgb", {"frames", "video", "start_time", "fps", "camera", "camera_sigma"});
  RgbConfig config;
  if (rgb.has("frames") && rgb.has("video")) {
    rgb.fail("video", "give either 'frames' (a frames.csv) or 'video', not both");
  }
  if (rgb.has("video")) {
    RgbVideoConfig video;
    video.video = rgb.text("video");
    video.start_time = rgb.numberInRange("start_time", -kMaxAbsTimeS, kMaxAbsTimeS);
    video.fps = rgb.positiveNumberUpTo("fps", kMaxFrameRateHz);
    rememberFileKey(survey, rgb, "video");
    config.video = video;
  } else {
    if (!rgb.has("frames")) {
      rgb.fail("frames", "missing required key: give 'frames' (a frames.csv) or 'video'");
    }
    for (const char* key : {"start_time", "fps"}) {
      if (rgb.has(key)) rgb.fail(key, "only allowed together with 'video'");
    }
    config.frames = rgb.text("frames");
    rememberFileKey(survey, rgb, "frames");
  }
  config.camera = readPinholeRadtanCamera(rgb, "camera");
  if (rgb.has("camera_sigma")) config.camera_sigma = readPinholeRadtanSigma(rgb, "camera_sigma");
  return config;
}

UhiConfig parseUhi(const StrictYamlMap& root, SurveyConfig& survey) {
  const StrictYamlMap uhi = root.map(
      "uhi", {"cube", "lines", "camera", "camera_sigma", "extrinsic", "time_offset_s",
              "time_offset_sigma_s"});
  UhiConfig config;
  config.cube = uhi.text("cube");
  config.lines = uhi.text("lines");
  rememberFileKey(survey, uhi, "cube");
  rememberFileKey(survey, uhi, "lines");
  config.camera = readPushbroomCamera(uhi, "camera");
  if (uhi.has("camera_sigma")) config.camera_sigma = readPushbroomSigma(uhi, "camera_sigma");
  const StrictYamlMap extrinsic = uhi.map(
      "extrinsic", {"rotation_wxyz", "translation_m", "sigma_rotation_deg", "sigma_translation_m"});
  config.T_C_U = readRigidTransform(extrinsic);
  config.sigma_rotation_deg = extrinsic.positiveNumberUpTo(
      "sigma_rotation_deg", kMaxRotationSigmaDeg, config.sigma_rotation_deg);
  config.sigma_translation_m = extrinsic.positiveNumberUpTo(
      "sigma_translation_m", kMaxTranslationSigmaM, config.sigma_translation_m);
  config.time_offset_s = uhi.numberInRange("time_offset_s", -kMaxAbsTimeOffsetS,
                                           kMaxAbsTimeOffsetS, config.time_offset_s);
  config.time_offset_sigma_s =
      uhi.positiveNumberUpTo("time_offset_sigma_s", kMaxTimeSigmaS, config.time_offset_sigma_s);
  return config;
}

InsConfig parseIns(const StrictYamlMap& root, SurveyConfig& survey) {
  const StrictYamlMap ins = root.map("ins", {"file", "camera_in_body", "sigma_horizontal_m",
                                             "sigma_depth_m", "sigma_attitude_deg"});
  InsConfig config;
  config.file = ins.text("file");
  rememberFileKey(survey, ins, "file");
  config.T_B_C = readRigidTransform(ins.map("camera_in_body", {"rotation_wxyz", "translation_m"}));
  config.sigma_horizontal_m =
      ins.positiveNumberUpTo("sigma_horizontal_m", kMaxPositionSigmaM, config.sigma_horizontal_m);
  config.sigma_depth_m =
      ins.positiveNumberUpTo("sigma_depth_m", kMaxPositionSigmaM, config.sigma_depth_m);
  const std::vector<double> sigma_attitude = ins.numbers(
      "sigma_attitude_deg", 3,
      {config.sigma_attitude_deg[0], config.sigma_attitude_deg[1], config.sigma_attitude_deg[2]});
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(sigma_attitude[i] > 0.0) || sigma_attitude[i] > kMaxRotationSigmaDeg) {
      ins.fail("sigma_attitude_deg", "expected three numbers in (0, 180], got " +
                                         formatDouble(sigma_attitude[i]) + " at position " +
                                         std::to_string(i + 1));
    }
    config.sigma_attitude_deg[i] = sigma_attitude[i];
  }
  return config;
}

SurveyConfig parseSurveyConfig(const std::filesystem::path& path, const YAML::Node& document) {
  if (document.IsNull()) {
    throw InputError(path, InputError::atLine(1),
                     std::string("empty file; expected a YAML map starting with 'format: ") +
                         SurveyConfig::kFormat + "'");
  }
  const StrictYamlMap root(path, document, "", 1,
                           {"format", "name", "rgb", "uhi", "ins", "origin", "lights"});
  const std::string format = root.text("format");
  if (format != SurveyConfig::kFormat) {
    root.fail("format",
              "unsupported format " + quoteForMessage(format) + "; expected '" + SurveyConfig::kFormat + "'");
  }
  SurveyConfig config;
  config.name = root.text("name");
  config.rgb = parseRgb(root, config);
  config.uhi = parseUhi(root, config);
  config.ins = parseIns(root, config);
  if (root.has("origin")) {
    const StrictYamlMap origin = root.map("origin", {"lat", "lon", "depth"});
    GeodeticPoint value;
    value.lat_deg = origin.numberInRange("lat", -90.0, 90.0);
    value.lon_deg = origin.numberInRange("lon", -180.0, 180.0);
    value.depth_m = origin.numberInRange("depth", kMinDepthM, kMaxDepthM);
    config.origin = value;
  }
  if (root.has("lights")) {
    const StrictYamlMap lights = root.map("lights", {"response", "lamps"});
    config.lights = readLightsConfig(lights);
    rememberFileKey(config, lights, "response");
  }
  return config;
}

void emitPath(YAML::Emitter& out, const char* key, const std::filesystem::path& path) {
  out << YAML::Key << key << YAML::Value << path.generic_string();
}

void emitNumberKey(YAML::Emitter& out, const char* key, double value) {
  out << YAML::Key << key << YAML::Value;
  emitNumber(out, value);
}

std::string emitSurveyConfig(const SurveyConfig& config) {
  YAML::Emitter out;
  out << YAML::Comment("hsmap survey description (format: see docs/SURVEY_FORMAT.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << SurveyConfig::kFormat;
  out << YAML::Key << "name" << YAML::Value << config.name;

  out << YAML::Key << "rgb" << YAML::Value << YAML::BeginMap;
  if (config.rgb.video) {
    emitPath(out, "video", config.rgb.video->video);
    emitNumberKey(out, "start_time", config.rgb.video->start_time);
    emitNumberKey(out, "fps", config.rgb.video->fps);
  } else {
    emitPath(out, "frames", config.rgb.frames);
  }
  out << YAML::Key << "camera" << YAML::Value;
  emitPinholeRadtanCamera(out, config.rgb.camera);
  if (config.rgb.camera_sigma) {
    out << YAML::Key << "camera_sigma" << YAML::Value;
    emitPinholeRadtanSigma(out, *config.rgb.camera_sigma);
  }
  out << YAML::EndMap;

  const UhiConfig& uhi = config.uhi;
  out << YAML::Key << "uhi" << YAML::Value << YAML::BeginMap;
  emitPath(out, "cube", uhi.cube);
  emitPath(out, "lines", uhi.lines);
  out << YAML::Key << "camera" << YAML::Value;
  emitPushbroomCamera(out, uhi.camera);
  if (uhi.camera_sigma) {
    out << YAML::Key << "camera_sigma" << YAML::Value;
    emitPushbroomSigma(out, *uhi.camera_sigma);
  }
  out << YAML::Key << "extrinsic" << YAML::Value << YAML::BeginMap;
  emitRigidTransformKeys(out, uhi.T_C_U);
  emitNumberKey(out, "sigma_rotation_deg", uhi.sigma_rotation_deg);
  emitNumberKey(out, "sigma_translation_m", uhi.sigma_translation_m);
  out << YAML::EndMap;
  emitNumberKey(out, "time_offset_s", uhi.time_offset_s);
  emitNumberKey(out, "time_offset_sigma_s", uhi.time_offset_sigma_s);
  out << YAML::EndMap;

  const InsConfig& ins = config.ins;
  out << YAML::Key << "ins" << YAML::Value << YAML::BeginMap;
  emitPath(out, "file", ins.file);
  out << YAML::Key << "camera_in_body" << YAML::Value << YAML::BeginMap;
  emitRigidTransformKeys(out, ins.T_B_C);
  out << YAML::EndMap;
  emitNumberKey(out, "sigma_horizontal_m", ins.sigma_horizontal_m);
  emitNumberKey(out, "sigma_depth_m", ins.sigma_depth_m);
  out << YAML::Key << "sigma_attitude_deg" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double sigma : ins.sigma_attitude_deg) emitNumber(out, sigma);
  out << YAML::EndSeq;
  out << YAML::EndMap;

  if (config.origin) {
    out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginMap;
    emitNumberKey(out, "lat", config.origin->lat_deg);
    emitNumberKey(out, "lon", config.origin->lon_deg);
    emitNumberKey(out, "depth", config.origin->depth_m);
    out << YAML::EndMap;
  }
  if (config.lights) {
    out << YAML::Key << "lights" << YAML::Value;
    emitLightsConfig(out, *config.lights);
  }
  out << YAML::EndMap;
  if (!out.good()) throw std::logic_error("writeSurveyConfig: YAML emitter: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

}  // namespace

SurveyConfig readSurveyConfig(const std::filesystem::path& path) {
  return parseSurveyConfig(path, loadYamlFile(path));
}

SurveyConfig parseSurveyConfigText(std::string_view raw, const std::filesystem::path& path) {
  return parseSurveyConfig(path, parseYamlText(raw, path));
}

void writeSurveyConfig(const std::filesystem::path& path, const SurveyConfig& config) {
  if (config.rgb.video && !config.rgb.frames.empty()) {
    throw std::invalid_argument("writeSurveyConfig: rgb has both 'frames' and 'video'");
  }
  const std::string text = emitSurveyConfig(config);
  // Run the reader's checks on the text before it reaches the disk, so hsmap
  // never writes a survey.yaml that it would itself refuse.
  try {
    parseSurveyConfig(path, YAML::Load(text));
  } catch (const InputError& e) {
    throw std::invalid_argument(std::string("writeSurveyConfig: invalid configuration: ") +
                                e.what());
  }
  AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace hsmap
