#include "pipelines/simulate/rgb_marine_snow.h"

#include <cmath>

#include "pipelines/simulate/sensor_noise.h"

namespace hsmap {

double marineSnowVolume(const MarineSnowConfig& config, const PinholeRadtanParameters& camera) {
  return (camera.width / camera.fx) * (camera.height / camera.fy) *
         (std::pow(config.max_range_m, 3) - std::pow(config.near_m, 3)) / 3.0;
}

std::vector<SnowParticle> sampleMarineSnow(const MarineSnowConfig& config,
                                           const PinholeRadtanParameters& camera, const SE3d& T_W_C,
                                           std::uint64_t frame_seed) {
  SensorNoise draws(frame_seed);
  const double mean = config.density_per_m3 * marineSnowVolume(config, camera);
  // Poisson: by products of uniforms when small, else its normal limit.
  long count = 0;
  if (mean < 30.0) {
    double product = draws.uniform01();
    const double limit = std::exp(-mean);
    while (product > limit) {
      ++count;
      product *= draws.uniform01();
    }
  } else {
    count = std::max(0L, std::lround(mean + std::sqrt(mean) * draws.normal()));
  }
  const double near3 = std::pow(config.near_m, 3);
  const double far3 = std::pow(config.max_range_m, 3);
  const double log_min = std::log(config.diameter_min_mm * 1e-3);
  const double log_max = std::log(config.diameter_max_mm * 1e-3);
  std::vector<SnowParticle> particles(static_cast<std::size_t>(count));
  for (SnowParticle& particle : particles) {
    const double z = std::cbrt(near3 + draws.uniform01() * (far3 - near3));
    const double u = -0.5 + draws.uniform01() * camera.width;
    const double v = -0.5 + draws.uniform01() * camera.height;
    const Eigen::Vector3d p_C(z * (u - camera.cx) / camera.fx, z * (v - camera.cy) / camera.fy, z);
    particle.p_W = T_W_C * p_C;
    particle.diameter_m = std::exp(log_min + draws.uniform01() * (log_max - log_min));
  }
  return particles;
}

}  // namespace hsmap
