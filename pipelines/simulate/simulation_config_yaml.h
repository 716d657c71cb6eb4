#pragma once
// The YAML file of `hsmap simulate --config FILE.yaml` (docs/SIMULATOR.md):
// a preset to start from and any subset of its settings to override. Reading
// is strict (strict_yaml_map.h): unknown keys, wrong types and values out of
// range are InputError naming the file, line and key.
//
//   format: hsmap-simulation/1       required
//   preset: rugged                    required: tiny, flat, low-relief, rugged, transect-100m
//   name, seed, start_time_s, origin: {lat, lon, depth}
//   scene:   terrain (flat | low-relief | rugged), seabed_depth_m, cell_m, slope_deg,
//            slope_direction_deg
//   motion:  pattern (transect | lawnmower), length_m, speed_m_s, speed_variation,
//            altitude_m, roll_pitch_amplitude_deg, heading_wander_deg, lanes, lane_spacing_m,
//            heading_deg
//   rgb:     width + height (the preset's camera scaled) or camera: {pinhole-radtan map},
//            rate_hz, samples_per_pixel, read_noise_dn, electrons_per_dn, exposure_reflectance,
//            blackouts: [{start_s, duration_s}, ...]
//   uhi:     samples (the preset's camera scaled) or camera: {pushbroom map}, bands,
//            wavelength_min_nm, wavelength_max_nm, rate_hz, ifov_across_deg, subsamples,
//            read_noise_dn, electrons_per_dn, exposure_reflectance
//   calibration: T_C_U: {rotation_wxyz, translation_m}, T_B_C: {...}, time_offset_s,
//            error_rotation_deg, error_translation_m, error_time_offset_s
//   ins:     rate_hz, horizontal_noise_m, horizontal_drift_m_per_sqrt_s, depth_noise_m,
//            depth_drift_m_per_sqrt_s, roll_pitch_noise_deg, heading_noise_deg,
//            attitude (true | false)
//   optics:  turbidity, lamp_power, lamp_separation_m, lamp_forward_m, lamp_beam_exponent,
//            shadows (true | false), backscatter: {phase_g, near_m, max_range_m, steps},
//            marine_snow: {density_per_m3, diameter_min_mm, diameter_max_mm, near_m,
//            max_range_m, albedo, aperture_mm}
//   truth:   ortho_pixel_m
#include <filesystem>

#include "pipelines/simulate/simulation_config.h"

namespace hsmap {

inline constexpr const char* kSimulationConfigFormat = "hsmap-simulation/1";

SimulationConfig readSimulationConfig(const std::filesystem::path& path);

}  // namespace hsmap
