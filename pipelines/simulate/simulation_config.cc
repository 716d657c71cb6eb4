#include "pipelines/simulate/simulation_config.h"

#include <cmath>
#include <stdexcept>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

// The vehicle layout shared by all presets. The RGB camera looks down with the
// top of its image forward: z_C = z_B (down), x_C = y_B (starboard),
// y_C = -x_B (aft). The UHI sits 12 cm aft of the camera, its line across
// the track (x_U ~ x_C), slightly misaligned as a real mount would be.
SimulatedCalibrationConfig vehicleCalibration() {
  SimulatedCalibrationConfig calibration;
  Eigen::Matrix3d R_B_C;
  R_B_C << 0, -1, 0,  //
      1, 0, 0,        //
      0, 0, 1;
  calibration.T_B_C.rotation = Eigen::Quaterniond(R_B_C);
  calibration.T_B_C.translation_m = Eigen::Vector3d(0.55, 0.0, 0.35);
  calibration.T_C_U.rotation = quaternionFromRollPitchHeadingDeg(0.8, -0.5, 1.2);
  calibration.T_C_U.translation_m = Eigen::Vector3d(0.02, 0.12, 0.01);
  calibration.time_offset_s = 0.015;
  return calibration;
}

}  // namespace

PinholeRadtanParameters scaledRgbCamera(int width, int height) {
  PinholeRadtanParameters camera;
  camera.width = width;
  camera.height = height;
  // 62 x 37 degrees field of view at any size: the footprint does not depend
  // on the resolution, only the ground sampling does.
  camera.fx = camera.fy = 800.0 * width / 960.0;
  camera.cx = (width - 1) / 2.0 + 0.8 * width / 960.0;
  camera.cy = (height - 1) / 2.0 - 1.1 * width / 960.0;
  camera.distortion = {-0.08, 0.02, 0.0004, -0.0003, 0.0};
  return camera;
}

PushbroomParameters scaledUhiCamera(int samples) {
  PushbroomParameters camera;
  camera.samples = samples;
  camera.f = 1500.0 * samples / 1920.0;  // 65 degrees across the line
  camera.cx = (samples - 1) / 2.0 + 2.5 * samples / 1920.0;
  camera.distortion = {0.015, -0.002};
  return camera;
}

namespace {

SimulationConfig baseConfig() {
  SimulationConfig config;
  config.rgb.camera = scaledRgbCamera(960, 540);
  config.uhi.camera = scaledUhiCamera(1920);
  config.calibration = vehicleCalibration();
  return config;
}

SimulationConfig twentyMetreTransect(const std::string& preset, TerrainPreset terrain) {
  SimulationConfig config = baseConfig();
  config.preset = preset;
  config.name = preset;
  config.scene.terrain = terrain;
  config.motion.length_m = 20.0;
  config.motion.speed_m_s = 0.4;
  config.motion.altitude_m = 2.0;
  return config;
}

void require(bool condition, const std::string& knob, const std::string& expected) {
  if (!condition) throw std::invalid_argument("simulation setting " + knob + ": expected " + expected);
}

}  // namespace

const std::vector<std::string>& simulationPresetNames() {
  static const std::vector<std::string> names{"tiny", "flat", "low-relief", "rugged",
                                              "transect-100m"};
  return names;
}

std::optional<SimulationConfig> simulationPreset(const std::string& name) {
  if (name == "flat") return twentyMetreTransect(name, TerrainPreset::flat);
  if (name == "low-relief") return twentyMetreTransect(name, TerrainPreset::low_relief);
  if (name == "rugged") return twentyMetreTransect(name, TerrainPreset::rugged);
  if (name == "transect-100m") {
    SimulationConfig config = twentyMetreTransect(name, TerrainPreset::low_relief);
    config.motion.length_m = 100.0;
    return config;
  }
  if (name == "tiny") {
    SimulationConfig config = baseConfig();
    config.preset = name;
    config.name = name;
    config.scene.terrain = TerrainPreset::low_relief;
    config.motion.length_m = 1.2;
    config.motion.speed_m_s = 0.3;
    config.motion.altitude_m = 1.5;
    config.rgb.camera = scaledRgbCamera(320, 180);
    config.rgb.samples_per_pixel = 2;
    config.uhi.camera = scaledUhiCamera(240);
    config.uhi.bands = 24;
    // Four seconds of survey: 1 Hz fixes of decimetre noise could not place
    // or scale it (fewer than 3 fixes within the video). A DVL-aided INS
    // logging at 10 Hz, centimetre-precise over such a short time, can.
    config.ins.rate_hz = 10.0;
    config.ins.horizontal_noise_m = 0.03;
    config.ins.depth_noise_m = 0.01;
    return config;
  }
  return std::nullopt;
}

void validateSimulationConfig(const SimulationConfig& config) {
  require(!config.name.empty(), "name", "a non-empty text");
  require(config.scene.cell_m >= 0.002 && config.scene.cell_m <= 0.5, "scene.cell_m",
          "a grid spacing in [0.002, 0.5] m");
  require(std::isfinite(config.scene.seabed_depth_m) && config.scene.seabed_depth_m > 5.0,
          "scene.seabed_depth_m", "a depth > 5 m");
  require(config.scene.slope_deg >= 0.0 && config.scene.slope_deg <= 45.0, "scene.slope_deg",
          "an angle in [0, 45] degrees");
  require(std::abs(config.scene.slope_direction_deg) <= 360.0, "scene.slope_direction_deg",
          "an angle in [-360, 360] degrees");
  const VehicleMotionConfig& motion = config.motion;
  require(motion.length_m > 0.0 && motion.length_m <= 10000.0, "motion.length_m",
          "a length in (0, 10000] m");
  require(motion.speed_m_s >= 0.02 && motion.speed_m_s <= 3.0, "motion.speed_m_s",
          "a speed in [0.02, 3] m/s");
  require(motion.speed_variation >= 0.0 && motion.speed_variation <= 0.9,
          "motion.speed_variation", "a fraction in [0, 0.9]");
  require(motion.altitude_m >= 0.5 && motion.altitude_m <= 10.0, "motion.altitude_m",
          "an altitude in [0.5, 10] m");
  require(motion.altitude_m < config.scene.seabed_depth_m - 1.0, "motion.altitude_m",
          "an altitude that keeps the vehicle below the surface");
  require(motion.roll_pitch_amplitude_deg >= 0.0 && motion.roll_pitch_amplitude_deg <= 20.0,
          "motion.roll_pitch_amplitude_deg", "an angle in [0, 20] degrees");
  require(motion.heading_wander_deg >= 0.0 && motion.heading_wander_deg <= 30.0,
          "motion.heading_wander_deg", "an angle in [0, 30] degrees");
  require(std::abs(motion.heading_deg) <= 360.0, "motion.heading_deg",
          "an angle in [-360, 360] degrees");
  require(motion.lanes >= 1 && motion.lanes <= 100, "motion.lanes", "an integer in [1, 100]");
  require(motion.lane_spacing_m > 0.0, "motion.lane_spacing_m", "a spacing > 0 m");
  // Uphill of the start the seabed rises by tan(slope) per metre: it must
  // stay deep enough under the whole path (lanes, U-turns, the 3 m the scene
  // extends beyond them) for the vehicle to stay under water, with 1.5 m of
  // relief to spare.
  const double path_reach_m =
      std::hypot(motion.length_m + (motion.lanes > 1 ? motion.lane_spacing_m : 0.0),
                 (motion.lanes - 1) * motion.lane_spacing_m) + 3.0;
  const double shallowest_seabed_m = config.scene.seabed_depth_m - 1.5 -
                                     std::tan(config.scene.slope_deg * M_PI / 180.0) * path_reach_m;
  require(config.scene.slope_deg == 0.0 || shallowest_seabed_m > motion.altitude_m + 1.0,
          "scene.slope_deg",
          "a slope that keeps the seabed under the track deeper than the altitude + 2.5 m "
          "(lower it, or deepen scene.seabed_depth_m)");
  require(config.rgb.camera.width >= 16 && config.rgb.camera.height >= 16, "rgb.camera",
          "an image of at least 16 x 16 pixels");
  require(config.rgb.camera.fx > 0.0 && config.rgb.camera.fy > 0.0, "rgb.camera.fx/fy", "> 0");
  require(config.rgb.rate_hz > 0.0 && config.rgb.rate_hz <= 200.0, "rgb.rate_hz",
          "a rate in (0, 200] Hz");
  require(config.rgb.samples_per_pixel == 1 || config.rgb.samples_per_pixel == 2 ||
              config.rgb.samples_per_pixel == 4,
          "rgb.samples_per_pixel", "1, 2 or 4");
  require(config.rgb.read_noise_dn >= 0.0, "rgb.read_noise_dn", "a value >= 0");
  require(config.rgb.electrons_per_dn > 0.0, "rgb.electrons_per_dn", "a value > 0");
  require(config.rgb.exposure_reflectance > 0.0, "rgb.exposure_reflectance", "a value > 0");
  require(std::isfinite(config.rgb.exposure_s) && config.rgb.exposure_s >= 0.0 &&
              config.rgb.exposure_s <= 1.0 / config.rgb.rate_hz,
          "rgb.exposure_s", "an exposure time in [0, 1 / rate_hz] s (the shutter closes before the next frame)");
  const RgbVignettingConfig& vignetting = config.rgb.vignetting;
  require(vignetting.model == VignettingModel::polynomial ||
              (vignetting.k[0] == 0.0 && vignetting.k[1] == 0.0 && vignetting.k[2] == 0.0),
          "rgb.vignetting.k", "no coefficients unless the model is polynomial");
  require(std::isfinite(vignetting.k[0]) && std::isfinite(vignetting.k[1]) &&
              std::isfinite(vignetting.k[2]),
          "rgb.vignetting.k", "finite coefficients");
  const RgbAutoGainConfig& gain = config.rgb.auto_gain;
  if (gain.enabled) {
    require(gain.target_dn > 0.0 && gain.target_dn < 255.0, "rgb.auto_gain.target_dn",
            "a brightness in (0, 255) DN");
    require(gain.step_db > 0.0 && gain.step_db <= 20.0, "rgb.auto_gain.step_db",
            "a step in (0, 20] dB");
    require(gain.interval_s > 0.0 && gain.interval_s <= 3600.0, "rgb.auto_gain.interval_s",
            "an interval in (0, 3600] s");
    require(gain.deadband_db >= 0.0 && gain.deadband_db <= 40.0, "rgb.auto_gain.deadband_db",
            "a dead band in [0, 40] dB");
    require(gain.min_db >= -40.0 && gain.min_db <= gain.max_db && gain.max_db <= 40.0,
            "rgb.auto_gain.min_db/max_db", "a range within [-40, 40] dB with min_db <= max_db");
    require(gain.initial_db >= gain.min_db && gain.initial_db <= gain.max_db,
            "rgb.auto_gain.initial_db", "a gain in [min_db, max_db]");
  }
  require(config.rgb.encoding.jpeg_quality >= 1 && config.rgb.encoding.jpeg_quality <= 100,
          "rgb.encoding.jpeg_quality", "a quality in [1, 100]");
  require(config.rgb.encoding.format != RgbFrameFormat::h264 ||
              (config.rgb.camera.width % 2 == 0 && config.rgb.camera.height % 2 == 0),
          "rgb.encoding.format", "an image of even width and height for h264 (4:2:0 chroma)");
  for (const RgbBlackout& blackout : config.rgb.blackouts) {
    require(std::isfinite(blackout.start_s) && blackout.start_s >= 0.0, "rgb.blackouts.start_s",
            "a time >= 0 s from the trajectory's start");
    require(std::isfinite(blackout.duration_s) && blackout.duration_s > 0.0 &&
                blackout.duration_s <= 1e6,
            "rgb.blackouts.duration_s", "a duration in (0, 1e6] s");
  }
  require(config.uhi.camera.samples >= 8, "uhi.camera.samples", "at least 8 samples");
  require(config.uhi.camera.f > 0.0, "uhi.camera.f", "> 0");
  require(config.uhi.bands >= 1 && config.uhi.bands <= 1000, "uhi.bands",
          "an integer in [1, 1000]");
  require(config.uhi.wavelength_min_nm >= 350.0 && config.uhi.wavelength_max_nm <= 1000.0 &&
              (config.uhi.bands == 1 || config.uhi.wavelength_min_nm < config.uhi.wavelength_max_nm),
          "uhi.wavelength_min_nm/wavelength_max_nm",
          "an increasing range within [350, 1000] nm");
  require(config.uhi.rate_hz > 0.0 && config.uhi.rate_hz <= 1000.0, "uhi.rate_hz",
          "a rate in (0, 1000] Hz");
  require(config.uhi.ifov_across_deg >= 0.0 && config.uhi.ifov_across_deg < 5.0,
          "uhi.ifov_across_deg", "an angle in [0, 5) degrees (0: one pixel)");
  require(config.uhi.subsamples >= 1 && config.uhi.subsamples <= 4, "uhi.subsamples",
          "an integer in [1, 4]");
  require(config.uhi.read_noise_dn >= 0.0, "uhi.read_noise_dn", "a value >= 0");
  require(config.uhi.electrons_per_dn > 0.0, "uhi.electrons_per_dn", "a value > 0");
  require(config.uhi.exposure_reflectance > 0.0, "uhi.exposure_reflectance", "a value > 0");
  require(std::abs(config.calibration.time_offset_s) <= 1.0, "calibration.time_offset_s",
          "an offset within +-1 s");
  require(config.calibration.error_rotation_deg >= 0.0, "calibration.error_rotation_deg", ">= 0");
  require(config.calibration.error_translation_m >= 0.0, "calibration.error_translation_m",
          ">= 0");
  require(config.ins.rate_hz > 0.0 && config.ins.rate_hz <= 100.0, "ins.rate_hz",
          "a rate in (0, 100] Hz");
  require(config.optics.turbidity >= 0.0 && config.optics.turbidity <= 20.0,
          "optics.turbidity", "a factor in [0, 20]");
  require(config.optics.lamp_power > 0.0, "optics.lamp_power", "a value > 0");
  require(config.optics.lamp_beam_exponent >= 0.0, "optics.lamp_beam_exponent", ">= 0");
  const WaterBackscatterConfig& backscatter = config.optics.backscatter;
  if (backscatter.enabled) {
    require(backscatter.phase_g >= 0.0 && backscatter.phase_g <= 0.99, "optics.backscatter.phase_g",
            "an asymmetry in [0, 0.99]");
    require(backscatter.near_m >= 0.0 && backscatter.near_m < backscatter.max_range_m &&
                backscatter.max_range_m <= 100.0,
            "optics.backscatter.near_m/max_range_m", "0 <= near_m < max_range_m <= 100 m");
    require(backscatter.steps >= 8 && backscatter.steps <= 100000, "optics.backscatter.steps",
            "an integer in [8, 100000]");
  }
  const MarineSnowConfig& snow = config.optics.marine_snow;
  if (snow.enabled) {
    require(snow.density_per_m3 >= 0.0 && snow.density_per_m3 <= 1e5, "optics.marine_snow.density_per_m3",
            "a density in [0, 1e5] per m^3");
    require(snow.diameter_min_mm > 0.0 && snow.diameter_min_mm <= snow.diameter_max_mm &&
                snow.diameter_max_mm <= 100.0,
            "optics.marine_snow.diameter_min_mm/diameter_max_mm", "0 < min <= max <= 100 mm");
    require(snow.near_m > 0.0 && snow.near_m < snow.max_range_m && snow.max_range_m <= 20.0,
            "optics.marine_snow.near_m/max_range_m", "0 < near_m < max_range_m <= 20 m");
    require(snow.albedo > 0.0 && snow.albedo <= 1.0, "optics.marine_snow.albedo", "a reflectance in (0, 1]");
    require(snow.aperture_mm >= 0.0 && snow.aperture_mm <= 100.0, "optics.marine_snow.aperture_mm",
            "a diameter in [0, 100] mm");
  }
  require(config.truth.ortho_pixel_m >= 0.002 && config.truth.ortho_pixel_m <= 1.0,
          "truth.ortho_pixel_m", "a pixel size in [0.002, 1] m");
}

}  // namespace hsmap
