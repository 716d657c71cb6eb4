#include "core/survey/survey_config.h"

#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

double numberInRange(const StrictYamlMap& map, const std::string& key, double low, double high) {
  const double value = map.number(key);
  if (value < low || value > high) {
    map.fail(key, "expected a number in [" + formatDouble(low) + ", " + formatDouble(high) +
                      "], got " + formatDouble(value));
  }
  return value;
}

RgbConfig parseRgb(const StrictYamlMap& root) {
  const StrictYamlMap rgb = root.map("rgb", {"frames", "video", "start_time", "fps", "camera"});
  RgbConfig config;
  if (rgb.has("frames") && rgb.has("video")) {
    rgb.fail("video", "give either 'frames' (a frames.csv) or 'video', not both");
  }
  if (rgb.has("video")) {
    RgbVideoConfig video;
    video.video = rgb.text("video");
    video.start_time = rgb.number("start_time");
    video.fps = rgb.positiveNumber("fps");
    config.video = video;
  } else {
    if (!rgb.has("frames")) {
      rgb.fail("frames", "missing required key: give 'frames' (a frames.csv) or 'video'");
    }
    for (const char* key : {"start_time", "fps"}) {
      if (rgb.has(key)) rgb.fail(key, "only allowed together with 'video'");
    }
    config.frames = rgb.text("frames");
  }
  config.camera = readPinholeRadtanCamera(rgb, "camera");
  return config;
}

UhiConfig parseUhi(const StrictYamlMap& root) {
  const StrictYamlMap uhi = root.map(
      "uhi", {"cube", "lines", "camera", "extrinsic", "time_offset_s", "time_offset_sigma_s"});
  UhiConfig config;
  config.cube = uhi.text("cube");
  config.lines = uhi.text("lines");
  config.camera = readPushbroomCamera(uhi, "camera");
  const StrictYamlMap extrinsic = uhi.map(
      "extrinsic", {"rotation_wxyz", "translation_m", "sigma_rotation_deg", "sigma_translation_m"});
  config.T_C_U = readRigidTransform(extrinsic);
  config.sigma_rotation_deg =
      extrinsic.positiveNumber("sigma_rotation_deg", config.sigma_rotation_deg);
  config.sigma_translation_m =
      extrinsic.positiveNumber("sigma_translation_m", config.sigma_translation_m);
  config.time_offset_s = uhi.number("time_offset_s", config.time_offset_s);
  config.time_offset_sigma_s =
      uhi.positiveNumber("time_offset_sigma_s", config.time_offset_sigma_s);
  return config;
}

InsConfig parseIns(const StrictYamlMap& root) {
  const StrictYamlMap ins = root.map("ins", {"file", "camera_in_body", "sigma_horizontal_m",
                                             "sigma_depth_m", "sigma_attitude_deg"});
  InsConfig config;
  config.file = ins.text("file");
  config.T_B_C = readRigidTransform(ins.map("camera_in_body", {"rotation_wxyz", "translation_m"}));
  config.sigma_horizontal_m = ins.positiveNumber("sigma_horizontal_m", config.sigma_horizontal_m);
  config.sigma_depth_m = ins.positiveNumber("sigma_depth_m", config.sigma_depth_m);
  const std::vector<double> sigma_attitude = ins.numbers(
      "sigma_attitude_deg", 3,
      {config.sigma_attitude_deg[0], config.sigma_attitude_deg[1], config.sigma_attitude_deg[2]});
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(sigma_attitude[i] > 0.0)) {
      ins.fail("sigma_attitude_deg", "expected three numbers > 0, got " +
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
                           {"format", "name", "rgb", "uhi", "ins", "origin"});
  const std::string format = root.text("format");
  if (format != SurveyConfig::kFormat) {
    root.fail("format",
              "unsupported format '" + format + "'; expected '" + SurveyConfig::kFormat + "'");
  }
  SurveyConfig config;
  config.name = root.text("name");
  config.rgb = parseRgb(root);
  config.uhi = parseUhi(root);
  config.ins = parseIns(root);
  if (root.has("origin")) {
    const StrictYamlMap origin = root.map("origin", {"lat", "lon", "depth"});
    GeodeticPoint value;
    value.lat_deg = numberInRange(origin, "lat", -90.0, 90.0);
    value.lon_deg = numberInRange(origin, "lon", -180.0, 180.0);
    value.depth_m = origin.number("depth");
    config.origin = value;
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
  out << YAML::EndMap;

  const UhiConfig& uhi = config.uhi;
  out << YAML::Key << "uhi" << YAML::Value << YAML::BeginMap;
  emitPath(out, "cube", uhi.cube);
  emitPath(out, "lines", uhi.lines);
  out << YAML::Key << "camera" << YAML::Value;
  emitPushbroomCamera(out, uhi.camera);
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
  out << YAML::EndMap;
  if (!out.good()) throw std::logic_error("writeSurveyConfig: YAML emitter: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

}  // namespace

SurveyConfig readSurveyConfig(const std::filesystem::path& path) {
  return parseSurveyConfig(path, loadYamlFile(path));
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
