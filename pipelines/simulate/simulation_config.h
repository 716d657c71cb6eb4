#pragma once
// SimulationConfig: every knob of `hsmap simulate` (docs/SIMULATOR.md), and
// the named presets it starts from.
//
// A preset is a complete configuration; a YAML file (simulation_config_yaml.h)
// names a preset and overrides any subset of its keys. Units are SI except
// angles (degrees), wavelengths (nm) and image quantities (pixels, DN).
//
// Presets:
//   tiny           a few seconds over low relief, 320x180 RGB, 240 x 24-band UHI;
//                  simulates in seconds (tests, demo)
//   flat           20 m transect over a flat, rough seabed, default resolutions
//   low-relief     20 m transect over gentle relief (~0.2 m)
//   rugged         20 m transect over boulders, ridges and a steep slope (>= 1 m,
//                  with an overhanging rock)
//   transect-100m  100 m transect over low relief at full resolution (the scale case)
// Default resolutions: RGB 960x540 at 25 Hz, UHI 1920 samples x 211 bands
// (400-800 nm) at 30 Hz, INS at 1 Hz.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/geodetic_point.h"
#include "core/survey/camera_sigma.h"
#include "core/survey/survey_config.h"
#include "pipelines/simulate/motion/ins_synthesis.h"
#include "pipelines/simulate/rgb_auto_gain.h"
#include "pipelines/simulate/rgb_frame_writer.h"
#include "pipelines/simulate/rgb_marine_snow.h"
#include "pipelines/simulate/rgb_vignetting.h"
#include "pipelines/simulate/water_backscatter.h"
#include "pipelines/simulate/motion/vehicle_motion_config.h"
#include "pipelines/simulate/scene/terrain_preset.h"

namespace hsmap {

struct SimulatedSceneConfig {
  TerrainPreset terrain = TerrainPreset::rugged;
  double seabed_depth_m = 40.0;  // mean depth of the seabed below the origin
  double cell_m = 0.02;          // grid spacing of the seabed mesh
  // A plane added to the seabed (rocks included): it deepens by tan(slope_deg)
  // per metre towards slope_direction_deg (downhill, clockwise from north),
  // and is zero at the track's start. The vehicle keeps its altitude, so its
  // depth changes along the slope.
  double slope_deg = 0.0;            // in [0, 45]
  double slope_direction_deg = 0.0;  // in [-360, 360]
};

// A time span of the video with no picture (a dropout): its frames are
// written all black. Times are from the trajectory's start.
struct RgbBlackout {
  double start_s = 0.0;     // >= 0
  double duration_s = 0.0;  // > 0; frames with start_s <= t < start_s + duration_s are black
};

struct SimulatedRgbConfig {
  PinholeRadtanParameters camera;  // true intrinsics (also written to survey.yaml)
  double rate_hz = 25.0;
  int samples_per_pixel = 2;       // anti-aliasing (rgb_renderer.h): 1 centre, 2 quincunx,
                                   // 4 rotated grid
  double read_noise_dn = 1.0;      // Gaussian read noise (8-bit DN)
  double electrons_per_dn = 20.0;  // shot noise: variance = DN / electrons_per_dn
  double exposure_reflectance = 0.6;  // a Lambertian surface of this reflectance at the
                                      // nominal altitude, on the axis, is exposed to 250 DN
  std::vector<RgbBlackout> blackouts;  // video dropouts; the frames and their truth poses are
                                       // still written
  // Motion blur: the shutter is open for exposure_s, centred on the frame's
  // time (rgb_motion_blur.h); 0 is an instantaneous exposure (no blur).
  double exposure_s = 0.0;  // in [0, 1 / rate_hz]
  RgbVignettingConfig vignetting;  // relative illumination (rgb_vignetting.h); none by default
  RgbAutoGainConfig auto_gain;     // automatic gain (rgb_auto_gain.h); off by default
  RgbEncodingConfig encoding;      // png frames (default), jpeg frames or an h264 video
                                   // (rgb_frame_writer.h)
};

struct SimulatedUhiConfig {
  PushbroomParameters camera;       // true intrinsics (also written to survey.yaml)
  int bands = 211;
  double wavelength_min_nm = 400.0;  // centre of the first band
  double wavelength_max_nm = 800.0;  // centre of the last band
  double rate_hz = 30.0;
  double ifov_across_deg = 0.0;     // across-line field of view of a line; 0: one pixel's angle
  int subsamples = 2;               // rays per pixel along the line and across it (n x n)
  double read_noise_dn = 8.0;
  double electrons_per_dn = 2.0;
  double exposure_reflectance = 1.0;  // this reflectance on the axis at the nominal altitude
                                      // reaches 60000 DN in the brightest band
};

struct SimulatedCalibrationConfig {
  RigidTransformConfig T_B_C;  // exact, written to survey.yaml as camera_in_body
  RigidTransformConfig T_C_U;  // true extrinsic
  double time_offset_s = 0.015;  // true d: true UHI time = recorded time + d
  // The guess written to survey.yaml differs from the truth by these amounts
  // (rotation about a seeded random axis, translation along a seeded random
  // direction, time offset subtracted).
  double error_rotation_deg = 2.0;
  double error_translation_m = 0.05;
  double error_time_offset_s = 0.015;
  // survey.yaml's UHI camera: the truth (uhi.camera) moved by these (0: the
  // exact intrinsics, as before), and the 1-sigma written as
  // uhi.camera_sigma (absent: none, the intrinsics are held fixed).
  double error_uhi_focal_rel = 0.0;              // f_guess = f (1 + e)
  double error_uhi_cx_px = 0.0;                  // cx_guess = cx + e
  std::array<double, 2> error_uhi_distortion{0.0, 0.0};  // k_guess = k + e
  std::optional<PushbroomSigma> uhi_camera_sigma;
  // The same for survey.yaml's RGB camera (rgb.camera): fx and fy both
  // scaled by (1 + e), cx + e, cy + e, [k1, k2, p1, p2, k3] + e; the 1-sigma
  // written as rgb.camera_sigma (absent: none, held fixed).
  double error_rgb_focal_rel = 0.0;
  double error_rgb_cx_px = 0.0;
  double error_rgb_cy_px = 0.0;
  std::array<double, 5> error_rgb_distortion{0.0, 0.0, 0.0, 0.0, 0.0};
  std::optional<PinholeRadtanSigma> rgb_camera_sigma;
};

struct SimulatedOpticsConfig {
  // Water: c(lambda) = pure-water-like absorption + coloured dissolved matter +
  // particles (water_attenuation.h); `turbidity` scales the last two.
  double turbidity = 1.0;
  double lamp_power = 1.0;          // relative; exposure is normalised anyway
  double lamp_separation_m = 0.6;   // two lamps, port and starboard of the camera
  double lamp_forward_m = 0.3;      // ahead of the RGB camera
  double lamp_beam_exponent = 2.0;  // intensity ~ cos^n of the angle off the lamp axis
  bool shadows = true;              // cast shadow rays towards the lamps
  WaterBackscatterConfig backscatter;  // light scattered into the cameras (water_backscatter.h);
                                       // off by default
  MarineSnowConfig marine_snow;  // particles lit in front of the RGB camera (rgb_marine_snow.h);
                                 // off by default
};

struct SimulatedTruthConfig {
  double ortho_pixel_m = 0.01;  // truth/reflectance pixel size
};

struct SimulationConfig {
  std::string preset;  // the preset this configuration started from
  std::string name;    // survey name (survey.yaml `name`)
  std::uint64_t seed = 1;
  GeodeticPoint origin{43.0, 5.0, 0.0};  // W is tangent here; seabed depth is below it
  double start_time_s = 36000.0;          // clock time of the trajectory's start
  SimulatedSceneConfig scene;
  VehicleMotionConfig motion;
  SimulatedRgbConfig rgb;
  SimulatedUhiConfig uhi;
  SimulatedCalibrationConfig calibration;
  InsNoiseConfig ins;
  SimulatedOpticsConfig optics;
  SimulatedTruthConfig truth;
};

// The presets' camera models at another resolution, with the same field of
// view (focal lengths and principal points scale with the width / samples).
PinholeRadtanParameters scaledRgbCamera(int width, int height);
PushbroomParameters scaledUhiCamera(int samples);

// Names of the presets, in the order above.
const std::vector<std::string>& simulationPresetNames();
// The preset `name`; std::nullopt for an unknown name.
std::optional<SimulationConfig> simulationPreset(const std::string& name);
// Throws std::invalid_argument naming the first knob out of its range.
void validateSimulationConfig(const SimulationConfig& config);

}  // namespace hsmap
