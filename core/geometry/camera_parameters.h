#pragma once
// Plain intrinsic parameter sets of hsmap's two camera models, as they appear
// in survey.yaml (`rgb.camera`, `uhi.camera`) and truth/calibration.yaml.
// The models themselves (projection, unprojection, Jacobians) live in
// pinhole_radtan_camera.h and pushbroom_camera.h.

#include <array>

namespace hsmap {

// OpenCV's pinhole model with radial-tangential distortion
// (distortion = [k1, k2, p1, p2, k3]); pixel centres at integer coordinates.
struct PinholeRadtanParameters {
  int width = 0;
  int height = 0;
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  std::array<double, 5> distortion{0.0, 0.0, 0.0, 0.0, 0.0};
};

// Push-broom line camera of docs/SURVEY_FORMAT.md: x = x_U / z_U,
// x_d = x (1 + k1 x^2 + k2 x^4), u = f x_d + cx; the scan line is y_U / z_U = 0.
struct PushbroomParameters {
  int samples = 0;
  double f = 0.0;
  double cx = 0.0;
  std::array<double, 2> distortion{0.0, 0.0};
};

}  // namespace hsmap
