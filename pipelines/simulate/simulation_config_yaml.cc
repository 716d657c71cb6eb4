#include "pipelines/simulate/simulation_config_yaml.h"

#include <stdexcept>

#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

int integer(const StrictYamlMap& map, const std::string& key, int default_value) {
  return map.has(key) ? map.positiveInteger(key) : default_value;
}

double nonNegative(const StrictYamlMap& map, const std::string& key, double default_value) {
  const double value = map.number(key, default_value);
  if (value < 0.0) map.fail(key, "expected a number >= 0, got " + formatDouble(value));
  return value;
}

bool boolean(const StrictYamlMap& map, const std::string& key, bool default_value) {
  if (!map.has(key)) return default_value;
  const std::string text = map.text(key);
  if (text == "true") return true;
  if (text == "false") return false;
  map.fail(key, "expected true or false, got '" + text + "'");
}

void readScene(const StrictYamlMap& root, SimulationConfig& config) {
  if (!root.has("scene")) return;
  const StrictYamlMap scene = root.map(
      "scene", {"terrain", "seabed_depth_m", "cell_m", "slope_deg", "slope_direction_deg"});
  if (scene.has("terrain")) {
    const std::string name = scene.text("terrain");
    const auto terrain = parseTerrainPreset(name);
    if (!terrain) scene.fail("terrain", "expected flat, low-relief or rugged, got '" + name + "'");
    config.scene.terrain = *terrain;
  }
  config.scene.seabed_depth_m = scene.positiveNumber("seabed_depth_m", config.scene.seabed_depth_m);
  config.scene.cell_m = scene.positiveNumber("cell_m", config.scene.cell_m);
  config.scene.slope_deg = scene.numberInRange("slope_deg", 0.0, 45.0, config.scene.slope_deg);
  config.scene.slope_direction_deg = scene.numberInRange(
      "slope_direction_deg", -360.0, 360.0, config.scene.slope_direction_deg);
}

void readMotion(const StrictYamlMap& root, SimulationConfig& config) {
  if (!root.has("motion")) return;
  const StrictYamlMap motion = root.map(
      "motion", {"pattern", "length_m", "speed_m_s", "speed_variation", "altitude_m",
                 "roll_pitch_amplitude_deg", "heading_wander_deg", "lanes", "lane_spacing_m",
                 "heading_deg"});
  VehicleMotionConfig& m = config.motion;
  if (motion.has("pattern")) {
    const std::string pattern = motion.text("pattern");
    if (pattern == "transect") {
      m.pattern = MotionPattern::transect;
    } else if (pattern == "lawnmower") {
      m.pattern = MotionPattern::lawnmower;
    } else {
      motion.fail("pattern", "expected transect or lawnmower, got '" + pattern + "'");
    }
  }
  m.length_m = motion.positiveNumber("length_m", m.length_m);
  m.speed_m_s = motion.positiveNumber("speed_m_s", m.speed_m_s);
  m.speed_variation = nonNegative(motion, "speed_variation", m.speed_variation);
  m.altitude_m = motion.positiveNumber("altitude_m", m.altitude_m);
  m.roll_pitch_amplitude_deg =
      nonNegative(motion, "roll_pitch_amplitude_deg", m.roll_pitch_amplitude_deg);
  m.heading_wander_deg = nonNegative(motion, "heading_wander_deg", m.heading_wander_deg);
  m.lanes = integer(motion, "lanes", m.lanes);
  m.lane_spacing_m = motion.positiveNumber("lane_spacing_m", m.lane_spacing_m);
  m.heading_deg = motion.numberInRange("heading_deg", -360.0, 360.0, m.heading_deg);
  if (m.pattern == MotionPattern::lawnmower && m.lanes < 2) {
    motion.fail("lanes", "expected at least 2 lanes for a lawnmower pattern");
  }
}

// rgb.blackouts: a list of {start_s, duration_s} maps. StrictYamlMap reads
// maps only, so the list is walked here and each item read as its own map.
std::vector<RgbBlackout> readBlackouts(const StrictYamlMap& rgb, const YAML::Node& list) {
  if (!list.IsSequence()) {
    rgb.fail("blackouts", "expected a list of {start_s, duration_s}, got " + describeYamlNode(list));
  }
  std::vector<RgbBlackout> blackouts;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = list[i];
    const long long line = item.Mark().line >= 0 ? item.Mark().line + 1 : rgb.lineOf("blackouts");
    const StrictYamlMap span(rgb.file(), item, rgb.keyPath("blackouts") + "[" + std::to_string(i) + "]",
                             line, {"start_s", "duration_s"});
    RgbBlackout blackout;
    blackout.start_s = span.numberInRange("start_s", 0.0, 1e6);
    blackout.duration_s = span.positiveNumberUpTo("duration_s", 1e6);
    blackouts.push_back(blackout);
  }
  return blackouts;
}

// rgb.vignetting: {model: none | cos4 | polynomial, k: [k1, k2, k3]}.
RgbVignettingConfig readVignetting(const StrictYamlMap& rgb) {
  const StrictYamlMap map = rgb.map("vignetting", {"model", "k"});
  RgbVignettingConfig vignetting;
  const std::string model = map.text("model");
  if (model == "none") {
    vignetting.model = VignettingModel::none;
  } else if (model == "cos4") {
    vignetting.model = VignettingModel::cos4;
  } else if (model == "polynomial") {
    vignetting.model = VignettingModel::polynomial;
  } else {
    map.fail("model", "expected none, cos4 or polynomial, got '" + model + "'");
  }
  if (vignetting.model != VignettingModel::polynomial) {
    if (map.has("k")) map.fail("k", "only allowed with model: polynomial");
    return vignetting;
  }
  const std::vector<double> k = map.numbers("k", 3);  // V = 1 + k1 r^2 + k2 r^4 + k3 r^6
  for (int i = 0; i < 3; ++i) vignetting.k[i] = k[i];
  return vignetting;
}

// rgb.auto_gain: present means on; every key has a default.
RgbAutoGainConfig readAutoGain(const StrictYamlMap& rgb) {
  const StrictYamlMap map = rgb.map("auto_gain", {"target_dn", "step_db", "interval_s", "deadband_db",
                                                  "min_db", "max_db", "initial_db"});
  RgbAutoGainConfig gain;
  gain.enabled = true;
  gain.target_dn = map.numberInRange("target_dn", 1.0, 254.0, gain.target_dn);
  gain.step_db = map.numberInRange("step_db", 0.01, 20.0, gain.step_db);
  gain.interval_s = map.numberInRange("interval_s", 0.001, 3600.0, gain.interval_s);
  gain.deadband_db = map.numberInRange("deadband_db", 0.0, 40.0, gain.deadband_db);
  gain.min_db = map.numberInRange("min_db", -40.0, 40.0, gain.min_db);
  gain.max_db = map.numberInRange("max_db", -40.0, 40.0, gain.max_db);
  if (gain.max_db < gain.min_db) map.fail("max_db", "expected max_db >= min_db");
  gain.initial_db = map.numberInRange("initial_db", gain.min_db, gain.max_db, gain.initial_db);
  return gain;
}

// rgb.encoding: {format: png | jpeg | h264, jpeg_quality: 1..100}.
RgbEncodingConfig readEncoding(const StrictYamlMap& rgb) {
  const StrictYamlMap map = rgb.map("encoding", {"format", "jpeg_quality"});
  RgbEncodingConfig encoding;
  const std::string format = map.text("format");
  if (format == "png") {
    encoding.format = RgbFrameFormat::png;
  } else if (format == "jpeg") {
    encoding.format = RgbFrameFormat::jpeg;
  } else if (format == "h264") {
    encoding.format = RgbFrameFormat::h264;
  } else {
    map.fail("format", "expected png, jpeg or h264, got '" + format + "'");
  }
  if (map.has("jpeg_quality")) {
    if (encoding.format != RgbFrameFormat::jpeg) map.fail("jpeg_quality", "only allowed with format: jpeg");
    encoding.jpeg_quality = map.positiveIntegerUpTo("jpeg_quality", 100);
  }
  return encoding;
}

void readRgb(const StrictYamlMap& root, const YAML::Node& rgb_node, SimulationConfig& config) {
  if (!root.has("rgb")) return;
  const StrictYamlMap rgb =
      root.map("rgb", {"width", "height", "camera", "rate_hz", "samples_per_pixel",
                       "read_noise_dn", "electrons_per_dn", "exposure_reflectance", "blackouts",
                       "exposure_s", "vignetting", "auto_gain", "encoding"});
  SimulatedRgbConfig& r = config.rgb;
  if (rgb.has("camera") && (rgb.has("width") || rgb.has("height"))) {
    rgb.fail("camera", "give either camera or width and height, not both");
  }
  if (rgb.has("camera")) {
    r.camera = readPinholeRadtanCamera(rgb, "camera");
  } else if (rgb.has("width") || rgb.has("height")) {
    r.camera = scaledRgbCamera(rgb.positiveInteger("width"), rgb.positiveInteger("height"));
  }
  r.rate_hz = rgb.positiveNumber("rate_hz", r.rate_hz);
  r.samples_per_pixel = integer(rgb, "samples_per_pixel", r.samples_per_pixel);
  if (r.samples_per_pixel != 1 && r.samples_per_pixel != 2 && r.samples_per_pixel != 4) {
    rgb.fail("samples_per_pixel", "expected 1, 2 or 4, got " + std::to_string(r.samples_per_pixel));
  }
  r.read_noise_dn = nonNegative(rgb, "read_noise_dn", r.read_noise_dn);
  r.electrons_per_dn = rgb.positiveNumber("electrons_per_dn", r.electrons_per_dn);
  r.exposure_reflectance = rgb.positiveNumber("exposure_reflectance", r.exposure_reflectance);
  if (rgb.has("blackouts")) r.blackouts = readBlackouts(rgb, rgb_node["blackouts"]);
  r.exposure_s = rgb.numberInRange("exposure_s", 0.0, 1.0 / r.rate_hz, r.exposure_s);
  if (rgb.has("vignetting")) r.vignetting = readVignetting(rgb);
  if (rgb.has("auto_gain")) r.auto_gain = readAutoGain(rgb);
  if (rgb.has("encoding")) r.encoding = readEncoding(rgb);
}

void readUhi(const StrictYamlMap& root, SimulationConfig& config) {
  if (!root.has("uhi")) return;
  const StrictYamlMap uhi = root.map(
      "uhi", {"samples", "camera", "bands", "wavelength_min_nm", "wavelength_max_nm", "rate_hz",
              "ifov_across_deg", "subsamples", "read_noise_dn", "electrons_per_dn",
              "exposure_reflectance"});
  SimulatedUhiConfig& u = config.uhi;
  if (uhi.has("camera") && uhi.has("samples")) {
    uhi.fail("camera", "give either camera or samples, not both");
  }
  if (uhi.has("camera")) {
    u.camera = readPushbroomCamera(uhi, "camera");
  } else if (uhi.has("samples")) {
    u.camera = scaledUhiCamera(uhi.positiveInteger("samples"));
  }
  u.bands = integer(uhi, "bands", u.bands);
  u.wavelength_min_nm = uhi.positiveNumber("wavelength_min_nm", u.wavelength_min_nm);
  u.wavelength_max_nm = uhi.positiveNumber("wavelength_max_nm", u.wavelength_max_nm);
  u.rate_hz = uhi.positiveNumber("rate_hz", u.rate_hz);
  u.ifov_across_deg = nonNegative(uhi, "ifov_across_deg", u.ifov_across_deg);
  u.subsamples = integer(uhi, "subsamples", u.subsamples);
  u.read_noise_dn = nonNegative(uhi, "read_noise_dn", u.read_noise_dn);
  u.electrons_per_dn = uhi.positiveNumber("electrons_per_dn", u.electrons_per_dn);
  u.exposure_reflectance = uhi.positiveNumber("exposure_reflectance", u.exposure_reflectance);
}

void readCalibration(const StrictYamlMap& root, SimulationConfig& config) {
  if (!root.has("calibration")) return;
  const StrictYamlMap calibration = root.map(
      "calibration", {"T_C_U", "T_B_C", "time_offset_s", "error_rotation_deg", "error_translation_m",
                      "error_time_offset_s", "error_uhi_focal_rel", "error_uhi_cx_px", "error_uhi_distortion",
                      "uhi_camera_sigma", "error_rgb_focal_rel", "error_rgb_cx_px", "error_rgb_cy_px",
                      "error_rgb_distortion", "rgb_camera_sigma"});
  SimulatedCalibrationConfig& c = config.calibration;
  if (calibration.has("T_C_U")) {
    c.T_C_U = readRigidTransform(calibration.map("T_C_U", {"rotation_wxyz", "translation_m"}));
  }
  if (calibration.has("T_B_C")) {
    c.T_B_C = readRigidTransform(calibration.map("T_B_C", {"rotation_wxyz", "translation_m"}));
  }
  c.time_offset_s = calibration.number("time_offset_s", c.time_offset_s);
  c.error_rotation_deg = nonNegative(calibration, "error_rotation_deg", c.error_rotation_deg);
  c.error_translation_m = nonNegative(calibration, "error_translation_m", c.error_translation_m);
  c.error_time_offset_s = calibration.number("error_time_offset_s", c.error_time_offset_s);
  c.error_uhi_focal_rel = calibration.numberInRange("error_uhi_focal_rel", -0.5, 0.5, c.error_uhi_focal_rel);
  c.error_uhi_cx_px = calibration.numberInRange("error_uhi_cx_px", -1e4, 1e4, c.error_uhi_cx_px);
  const std::vector<double> distortion = calibration.numbers(
      "error_uhi_distortion", 2, {c.error_uhi_distortion[0], c.error_uhi_distortion[1]});
  c.error_uhi_distortion = {distortion[0], distortion[1]};
  if (calibration.has("uhi_camera_sigma")) c.uhi_camera_sigma = readPushbroomSigma(calibration, "uhi_camera_sigma");
  c.error_rgb_focal_rel = calibration.numberInRange("error_rgb_focal_rel", -0.5, 0.5, c.error_rgb_focal_rel);
  c.error_rgb_cx_px = calibration.numberInRange("error_rgb_cx_px", -1e4, 1e4, c.error_rgb_cx_px);
  c.error_rgb_cy_px = calibration.numberInRange("error_rgb_cy_px", -1e4, 1e4, c.error_rgb_cy_px);
  const std::vector<double> rgb_distortion = calibration.numbers(
      "error_rgb_distortion", 5, std::vector<double>(c.error_rgb_distortion.begin(), c.error_rgb_distortion.end()));
  for (std::size_t i = 0; i < 5; ++i) c.error_rgb_distortion[i] = rgb_distortion[i];
  if (calibration.has("rgb_camera_sigma")) c.rgb_camera_sigma = readPinholeRadtanSigma(calibration, "rgb_camera_sigma");
}

void readIns(const StrictYamlMap& root, SimulationConfig& config) {
  if (!root.has("ins")) return;
  const StrictYamlMap ins = root.map(
      "ins", {"rate_hz", "horizontal_noise_m", "horizontal_drift_m_per_sqrt_s", "depth_noise_m",
              "depth_drift_m_per_sqrt_s", "roll_pitch_noise_deg", "heading_noise_deg",
              "attitude"});
  InsNoiseConfig& n = config.ins;
  n.rate_hz = ins.positiveNumber("rate_hz", n.rate_hz);
  n.horizontal_noise_m = nonNegative(ins, "horizontal_noise_m", n.horizontal_noise_m);
  n.horizontal_drift_m_per_sqrt_s =
      nonNegative(ins, "horizontal_drift_m_per_sqrt_s", n.horizontal_drift_m_per_sqrt_s);
  n.depth_noise_m = nonNegative(ins, "depth_noise_m", n.depth_noise_m);
  n.depth_drift_m_per_sqrt_s =
      nonNegative(ins, "depth_drift_m_per_sqrt_s", n.depth_drift_m_per_sqrt_s);
  n.roll_pitch_noise_deg = nonNegative(ins, "roll_pitch_noise_deg", n.roll_pitch_noise_deg);
  n.heading_noise_deg = nonNegative(ins, "heading_noise_deg", n.heading_noise_deg);
  n.attitude = boolean(ins, "attitude", n.attitude);
}

// optics.backscatter: present means on; every key has a default.
WaterBackscatterConfig readBackscatter(const StrictYamlMap& optics) {
  const StrictYamlMap map = optics.map("backscatter", {"phase_g", "near_m", "max_range_m", "steps"});
  WaterBackscatterConfig backscatter;
  backscatter.enabled = true;
  backscatter.phase_g = map.numberInRange("phase_g", 0.0, 0.99, backscatter.phase_g);
  backscatter.near_m = map.numberInRange("near_m", 0.0, 1.0, backscatter.near_m);
  backscatter.max_range_m = map.numberInRange("max_range_m", 0.1, 100.0, backscatter.max_range_m);
  if (backscatter.max_range_m <= backscatter.near_m) map.fail("max_range_m", "expected more than near_m");
  if (map.has("steps")) {
    backscatter.steps = map.positiveIntegerUpTo("steps", 100000);
    if (backscatter.steps < 8) map.fail("steps", "expected an integer in [8, 100000]");
  }
  return backscatter;
}

// optics.marine_snow: present means on; every key has a default.
MarineSnowConfig readMarineSnow(const StrictYamlMap& optics) {
  const StrictYamlMap map = optics.map("marine_snow", {"density_per_m3", "diameter_min_mm", "diameter_max_mm",
                                                       "near_m", "max_range_m", "albedo", "aperture_mm"});
  MarineSnowConfig snow;
  snow.enabled = true;
  snow.density_per_m3 = map.numberInRange("density_per_m3", 0.0, 1e5, snow.density_per_m3);
  snow.diameter_min_mm = map.positiveNumberUpTo("diameter_min_mm", 100.0, snow.diameter_min_mm);
  snow.diameter_max_mm = map.positiveNumberUpTo("diameter_max_mm", 100.0, snow.diameter_max_mm);
  if (snow.diameter_max_mm < snow.diameter_min_mm) map.fail("diameter_max_mm", "expected at least diameter_min_mm");
  snow.near_m = map.positiveNumberUpTo("near_m", 20.0, snow.near_m);
  snow.max_range_m = map.positiveNumberUpTo("max_range_m", 20.0, snow.max_range_m);
  if (snow.max_range_m <= snow.near_m) map.fail("max_range_m", "expected more than near_m");
  snow.albedo = map.positiveNumberUpTo("albedo", 1.0, snow.albedo);
  snow.aperture_mm = map.numberInRange("aperture_mm", 0.0, 100.0, snow.aperture_mm);
  return snow;
}

void readOptics(const StrictYamlMap& root, SimulationConfig& config) {
  if (!root.has("optics")) return;
  const StrictYamlMap optics =
      root.map("optics", {"turbidity", "lamp_power", "lamp_separation_m", "lamp_forward_m",
                          "lamp_beam_exponent", "shadows", "backscatter",
                          "marine_snow"});
  SimulatedOpticsConfig& o = config.optics;
  o.turbidity = nonNegative(optics, "turbidity", o.turbidity);
  o.lamp_power = optics.positiveNumber("lamp_power", o.lamp_power);
  o.lamp_separation_m = nonNegative(optics, "lamp_separation_m", o.lamp_separation_m);
  o.lamp_forward_m = optics.number("lamp_forward_m", o.lamp_forward_m);
  o.lamp_beam_exponent = nonNegative(optics, "lamp_beam_exponent", o.lamp_beam_exponent);
  o.shadows = boolean(optics, "shadows", o.shadows);
  if (optics.has("backscatter")) o.backscatter = readBackscatter(optics);
  if (optics.has("marine_snow")) o.marine_snow = readMarineSnow(optics);
}

}  // namespace

SimulationConfig readSimulationConfig(const std::filesystem::path& path) {
  const YAML::Node document = loadYamlFile(path);
  const StrictYamlMap root(path, document, "", 1,
                           {"format", "preset", "name", "seed", "start_time_s", "origin", "scene",
                            "motion", "rgb", "uhi", "calibration", "ins", "optics", "truth"});
  const std::string format = root.text("format");
  if (format != kSimulationConfigFormat) {
    root.fail("format", std::string("expected ") + kSimulationConfigFormat + ", got '" + format + "'");
  }
  const std::string preset = root.text("preset");
  std::optional<SimulationConfig> base = simulationPreset(preset);
  if (!base) {
    root.fail("preset", "expected one of " + joined(simulationPresetNames()) + ", got '" + preset + "'");
  }
  SimulationConfig config = *base;
  if (root.has("name")) config.name = root.text("name");
  if (root.has("seed")) {
    const double seed = root.number("seed");
    if (seed < 0.0 || seed != std::floor(seed) || seed > 9.0e15) {
      root.fail("seed", "expected an integer in [0, 9e15], got " + formatDouble(seed));
    }
    config.seed = static_cast<std::uint64_t>(seed);
  }
  config.start_time_s = root.number("start_time_s", config.start_time_s);
  if (root.has("origin")) {
    const StrictYamlMap origin = root.map("origin", {"lat", "lon", "depth"});
    config.origin.lat_deg = origin.number("lat");
    config.origin.lon_deg = origin.number("lon");
    config.origin.depth_m = origin.number("depth");
    if (std::abs(config.origin.lat_deg) > 90.0) origin.fail("lat", "expected a latitude in [-90, 90]");
    if (std::abs(config.origin.lon_deg) > 180.0) origin.fail("lon", "expected a longitude in [-180, 180]");
  }
  readScene(root, config);
  readMotion(root, config);
  readRgb(root, document["rgb"], config);
  readUhi(root, config);
  readCalibration(root, config);
  readIns(root, config);
  readOptics(root, config);
  if (root.has("truth")) {
    const StrictYamlMap truth = root.map("truth", {"ortho_pixel_m"});
    config.truth.ortho_pixel_m = truth.positiveNumber("ortho_pixel_m", config.truth.ortho_pixel_m);
  }
  try {
    validateSimulationConfig(config);
  } catch (const std::invalid_argument& error) {
    throw InputError(path, "", error.what());
  }
  return config;
}

}  // namespace hsmap
