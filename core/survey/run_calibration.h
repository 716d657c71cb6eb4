#pragma once
// RUN/calibration.yaml: a run's estimate of the RGB-UHI extrinsic T_C_U and
// of the UHI time offset d, with their 1-sigma (docs/EVALUATE.md):
//
//   format: hsmap-calibration/1
//   variant: joint                       stacked | planar | sequential | joint
//   T_C_U:
//     rotation_wxyz: [w, x, y, z]
//     translation_m: [x, y, z]           each in [-100, 100]
//     sigma_rotation_deg: [sx, sy, sz]   1-sigma of the rotation error about U's axes, or null
//     sigma_translation_m: [sx, sy, sz]  or null
//   time_offset_s: 0.0148                d: true UHI time = recorded time + d, in [-3600, 3600]
//   time_offset_sigma_s: 0.0004          or null
//   uhi_camera: {f: ..., cx: ..., distortion: [k1, k2],
//                sigma: {f: ..., cx: ..., distortion: [s1, s2]}}
//                                        optional: present when the run estimated the UHI's
//                                        intrinsics (a sigma of 0: held at survey.yaml's)
//   rgb_camera: {fx: ..., fy: ..., cx: ..., cy: ..., distortion: [k1, k2, p1, p2, k3],
//                sigma: {fx: ..., fy: ..., cx: ..., cy: ..., distortion: [5 sigmas]}}
//                                        optional: present when the run estimated the RGB
//                                        camera's intrinsics (georef's keyframe adjustment)
//   water: {...}                         optional: present when the radiometry stage estimated
//                                        the water and the lamps (water_estimate.h)
//   warnings: []                         texts, e.g. a component the survey cannot determine
//
// A sigma that was not estimated is `null`; every key but uhi_camera, rgb_camera and water is required (a sigma
// may be null, not absent), so a truncated file is never read as "not
// estimated". Sigmas are finite and >= 0. Rotations follow survey_config.h
// (norm within 1e-3 of 1, normalised; one unit to double precision is kept
// bit-exactly). Reading is strict (strict_yaml_map.h): unknown, duplicated
// or missing keys are InputError naming the file, line and key, e.g.
//   "RUN/calibration.yaml:line 7, key T_C_U.sigma_translation_m: expected a
//    list of 3 numbers >= 0 or null (not estimated), got 'abc'".
// Writing is atomic, numbers in shortest round-trip form, and runs the
// reader's checks first: std::invalid_argument for a calibration the reader
// would refuse.

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/survey/camera_sigma.h"
#include "core/survey/survey_config.h"
#include "core/survey/water_estimate.h"

namespace hsmap {

// The UHI intrinsics a run estimated (survey.yaml's uhi.camera keys without
// `model` and `samples`, which the survey states) and their 1-sigma.
struct UhiCameraEstimate {
  double f = 0.0;
  double cx = 0.0;
  std::array<double, 2> distortion{0.0, 0.0};
  PushbroomSigma sigma;

  // `survey_camera` (its model and samples) with these intrinsics.
  PushbroomParameters appliedTo(PushbroomParameters survey_camera) const;
};

// The RGB intrinsics a run estimated (survey.yaml's rgb.camera keys without
// `model`, `width` and `height`, which the survey states) and their 1-sigma.
struct RgbCameraEstimate {
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  std::array<double, 5> distortion{0.0, 0.0, 0.0, 0.0, 0.0};
  PinholeRadtanSigma sigma;

  // `survey_camera` (its model and image size) with these intrinsics.
  PinholeRadtanParameters appliedTo(PinholeRadtanParameters survey_camera) const;
};

struct RunCalibration {
  static constexpr const char* kFormat = "hsmap-calibration/1";
  std::string variant;          // one of runVariants() (run_variants.h)
  RigidTransformConfig T_C_U;   // U in the RGB camera frame C
  std::optional<Eigen::Vector3d> sigma_rotation_deg;   // about U's x, y, z; nullopt: not estimated
  std::optional<Eigen::Vector3d> sigma_translation_m;  // along C's x, y, z
  double time_offset_s = 0.0;                          // d
  std::optional<double> time_offset_sigma_s;
  std::optional<UhiCameraEstimate> uhi_camera;  // nullopt: survey.yaml's uhi.camera was used
  std::optional<RgbCameraEstimate> rgb_camera;  // nullopt: survey.yaml's rgb.camera was used
  std::optional<WaterEstimate> water;           // nullopt: no radiometry (its warnings are in `warnings`)
  std::vector<std::string> warnings;
};

RunCalibration readRunCalibration(const std::filesystem::path& file);
// The same on the file's content `text`; `file` names it in errors.
RunCalibration parseRunCalibration(std::string_view text, const std::filesystem::path& file);
void writeRunCalibration(const std::filesystem::path& file, const RunCalibration& calibration);

}  // namespace hsmap
