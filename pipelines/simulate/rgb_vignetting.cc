#include "pipelines/simulate/rgb_vignetting.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/geometry/pinhole_radtan_camera.h"

namespace hsmap {
namespace {

double factor(const RgbVignettingConfig& config, const PinholeRadtanCamera& lens, double u,
              double v) {
  const PinholeRadtanParameters& camera = lens.parameters();
  switch (config.model) {
    case VignettingModel::none:
      return 1.0;
    case VignettingModel::cos4: {
      const auto ray = lens.unproject(Eigen::Vector2d(u, v));
      if (!ray) throw std::invalid_argument("rgb.vignetting: a pixel of the camera has no ray");
      const double cos_theta = ray->normalized().z();
      return cos_theta * cos_theta * cos_theta * cos_theta;
    }
    case VignettingModel::polynomial: {
      const double half_diagonal = 0.5 * std::hypot(camera.width, camera.height);
      const double r2 = (std::pow(u - camera.cx, 2) + std::pow(v - camera.cy, 2)) /
                        (half_diagonal * half_diagonal);
      const double value = 1.0 + r2 * (config.k[0] + r2 * (config.k[1] + r2 * config.k[2]));
      return std::clamp(value, 0.0, 1.0);
    }
  }
  return 1.0;
}

}  // namespace

double vignettingFactor(const RgbVignettingConfig& config, const PinholeRadtanParameters& camera,
                        double u, double v) {
  return factor(config, PinholeRadtanCamera(camera), u, v);
}

std::vector<float> vignettingImage(const RgbVignettingConfig& config,
                                   const PinholeRadtanParameters& camera) {
  if (config.model == VignettingModel::none) return {};
  const PinholeRadtanCamera lens(camera);
  std::vector<float> image(std::size_t(camera.width) * camera.height);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      image[std::size_t(v) * camera.width + u] = float(factor(config, lens, u, v));
    }
  }
  return image;
}

}  // namespace hsmap
