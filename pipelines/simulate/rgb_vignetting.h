#pragma once
// Vignetting of the RGB camera (rgb.vignetting): the relative illumination
// V(u, v) of the image plane, by which the renderer multiplies each pixel's
// signal (before noise: it is optical, so shot noise follows it).
//
//   none        V = 1 (the default)
//   cos4        natural vignetting, the cosine-fourth law: V = cos^4(theta),
//               theta the angle of the pixel centre's ray off the optical axis
//               (through the true, distorted camera). For the presets' 62 x 37
//               degree camera it is 0.53 in the corners.
//   polynomial  a radial polynomial, as lens-correction profiles describe a
//               lens and housing: V = 1 + k1 r^2 + k2 r^4 + k3 r^6, with r the
//               distance from the principal point (cx, cy) over the half
//               diagonal of the image (r = 1 in a corner of a centred camera).
//               V is clamped to [0, 1].
#include <array>
#include <vector>

#include "core/geometry/camera_parameters.h"

namespace hsmap {

enum class VignettingModel { none, cos4, polynomial };

struct RgbVignettingConfig {
  VignettingModel model = VignettingModel::none;
  std::array<double, 3> k{0.0, 0.0, 0.0};  // polynomial only: k1, k2, k3
};

// V at pixel centre (u, v).
double vignettingFactor(const RgbVignettingConfig& config, const PinholeRadtanParameters& camera,
                        double u, double v);
// V of every pixel, row-major; empty for `none`.
std::vector<float> vignettingImage(const RgbVignettingConfig& config,
                                   const PinholeRadtanParameters& camera);

}  // namespace hsmap
