#include "pipelines/simulate/rgb_motion_blur.h"

#include <algorithm>
#include <cmath>

namespace hsmap {

double imageMotionPx(const PinholeRadtanCamera& camera, const MeshRayCaster& scene,
                     const SE3d& T_W_C_begin, const SE3d& T_W_C_end) {
  const SE3d T_C_W_end = T_W_C_end.inverse();
  double largest = 0.0;
  for (double fy : {0.05, 0.5, 0.95}) {
    for (double fx : {0.05, 0.5, 0.95}) {
      const Eigen::Vector2d pixel(fx * (camera.width() - 1), fy * (camera.height() - 1));
      const auto ray_C = camera.unproject(pixel);
      if (!ray_C) continue;
      const Eigen::Vector3d direction_W = T_W_C_begin.q * ray_C->normalized();
      const RayHit hit = scene.intersect(Ray{T_W_C_begin.t, direction_W});
      if (!hit.hit()) continue;
      const Eigen::Vector3d p_C_end = T_C_W_end * (T_W_C_begin.t + hit.distance * direction_W);
      if (p_C_end.z() <= 0.0) continue;
      largest = std::max(largest, (camera.project(p_C_end) - pixel).norm());
    }
  }
  return largest;
}

int motionBlurSubframes(double motion_px) {
  if (!(motion_px > 0.0)) return 1;
  return std::clamp(int(std::ceil(motion_px / kMaxSubframeStepPx)), 1, kMaxSubframes);
}

std::vector<double> subframeTimes(double t, double exposure_s, int subframes) {
  std::vector<double> times(subframes);
  for (int i = 0; i < subframes; ++i) {
    times[i] = subframes == 1 ? t : t - 0.5 * exposure_s + (i + 0.5) * exposure_s / subframes;
  }
  return times;
}

}  // namespace hsmap
