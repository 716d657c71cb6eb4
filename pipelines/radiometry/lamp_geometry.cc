#include "pipelines/radiometry/lamp_geometry.h"

#include <algorithm>
#include <cmath>

namespace hsmap {

LampsInWorld lampsInWorld(const LightsConfig& lights, const SE3d& T_W_U, const SE3d& T_C_U) {
  const SE3d T_W_C = T_W_U * T_C_U.inverse();
  const Eigen::Matrix3d R_W_C = T_W_C.rotationMatrix();
  LampsInWorld lamps;
  for (const LampConfig& lamp : lights.lamps) {
    lamps.p_W.push_back(T_W_C * lamp.p_C);
    lamps.axis_W.push_back((R_W_C * lamp.axis_C).normalized());
  }
  return lamps;
}

LampPathsAtPoint lampPathsAt(const LampsInWorld& lamps, const Eigen::Vector3d& p_W, Eigen::Vector3d n_W,
                             const Eigen::Vector3d& viewer_W, const MeshRayCaster* shadows,
                             double shadow_skip_m) {
  LampPathsAtPoint paths;
  if (n_W.dot(viewer_W - p_W) < 0.0) n_W = -n_W;
  for (std::size_t l = 0; l < lamps.p_W.size(); ++l) {
    const Eigen::Vector3d to_lamp = lamps.p_W[l] - p_W;
    const double range = to_lamp.norm();
    if (!(range > 0.0)) continue;
    const Eigen::Vector3d direction = to_lamp / range;
    const double cos_incidence = n_W.dot(direction);
    if (!(cos_incidence > 0.0)) {
      ++paths.facing_away;
      continue;
    }
    if (shadows != nullptr && range > 2.0 * shadow_skip_m) {
      Ray ray;
      ray.origin = p_W;
      ray.direction = direction;
      ray.t_near = shadow_skip_m;
      ray.t_far = range - shadow_skip_m;
      if (shadows->occluded(ray)) {
        ++paths.shadowed;
        continue;
      }
    }
    LampPath path;
    path.range_m = range;
    path.cos_incidence = std::min(1.0, cos_incidence);
    // θ_l: between the lamp's axis and the ray from the lamp to the point.
    path.off_axis_rad = std::acos(std::clamp(lamps.axis_W[l].dot(-direction), -1.0, 1.0));
    paths.lit.push_back(path);
  }
  return paths;
}

Eigen::Vector3d triangleNormal(const MeshRayCaster& mesh, int triangle) {
  const Eigen::Vector3i& t = mesh.triangles()[std::size_t(triangle)];
  const auto& v = mesh.vertices();
  return (v[std::size_t(t[1])] - v[std::size_t(t[0])]).cross(v[std::size_t(t[2])] - v[std::size_t(t[0])]).normalized();
}

}  // namespace hsmap
