#pragma once
// Camera intrinsics' 1-sigma as survey.yaml gives them (`rgb.camera_sigma`,
// `uhi.camera_sigma`, docs/SURVEY_FORMAT.md): how far the calibrated
// intrinsics of rgb.camera / uhi.camera may be from the truth. The contract
// says a camera with a sigma is self-calibrated; a sigma of 0 (the default of
// every absent key) holds that parameter fixed.
//
// They become priors where the intrinsics are estimated: the UHI's in the
// `joint` problem (docs/JOINT.md), the RGB camera's in the geo-referencing
// bundle adjustment (docs/GEOREF.md); loadSurvey says so when a sigma is > 0.
//
// Ranges (each optional inside the map, default 0):
//   f, fx, fy, cx, cy: pixels, in [0, 1e6] (as the camera's own values)
//   distortion: exactly 5 (RGB: k1, k2, p1, p2, k3) / 2 (UHI: k1, k2)
//               numbers, each in [0, 1000]

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>

#include "core/survey/strict_yaml_map.h"

namespace hsmap {

// 1-sigma of PinholeRadtanParameters' calibrated values (pixels; distortion unitless).
struct PinholeRadtanSigma {
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  std::array<double, 5> distortion{0.0, 0.0, 0.0, 0.0, 0.0};

  // True when some sigma is > 0, i.e. the survey asks for self-calibration.
  bool asksForCalibration() const;
};

// 1-sigma of PushbroomParameters' calibrated values (`samples` is exact).
struct PushbroomSigma {
  double f = 0.0;
  double cx = 0.0;
  std::array<double, 2> distortion{0.0, 0.0};

  bool asksForCalibration() const;
};

// Read the map at `parent.key` (which must be present). Throws InputError at
// the dotted key, e.g. "key uhi.camera_sigma.f: expected a number in [0, 1e+06], got -1".
PinholeRadtanSigma readPinholeRadtanSigma(const StrictYamlMap& parent, const std::string& key);
PushbroomSigma readPushbroomSigma(const StrictYamlMap& parent, const std::string& key);

// Emit the value of the map (flow style, every key, zeros included), so that
// it reads back to identical values.
void emitPinholeRadtanSigma(YAML::Emitter& out, const PinholeRadtanSigma& sigma);
void emitPushbroomSigma(YAML::Emitter& out, const PushbroomSigma& sigma);

}  // namespace hsmap
