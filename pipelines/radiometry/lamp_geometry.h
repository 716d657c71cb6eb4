#pragma once
// Where the vehicle's lamps are for one scan line, and the light path of each
// lamp to a seabed point (the geometry of the radiometric model,
// factors/lamp_radiance_factor.h; docs/RADIOMETRY.md).
//
// The lamps are stated in the RGB camera frame C (survey.yaml's `lights`).
// A scan line's pose is T_W_U, so the camera is at T_W_C = T_W_U · T_C_U⁻¹
// and lamp l sits at p_W = T_W_C · p_C with its axis R_W_C · axis_C.
//
// For a seabed point p_W with unit normal n_W (facing the UHI), lamp l
// lights it when the point faces the lamp (cos i_l = n · (lamp − p)/r_l > 0)
// and, when a shadow caster is given, when no triangle lies between them:
// the shadow ray leaves the point towards the lamp, skipping `shadow_skip_m`
// at both ends so that it finds neither the surface it starts on nor the
// lamp's own housing.

#include <Eigen/Core>
#include <vector>

#include "core/geometry/se3.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/lights_config.h"
#include "factors/lamp_radiance_factor.h"

namespace hsmap {

struct LampsInWorld {
  std::vector<Eigen::Vector3d> p_W;     // lamp centres
  std::vector<Eigen::Vector3d> axis_W;  // unit beam axes
};

// The lamps of `lights` for the scan line at T_W_U, through T_C_U.
LampsInWorld lampsInWorld(const LightsConfig& lights, const SE3d& T_W_U, const SE3d& T_C_U);

struct LampPathsAtPoint {
  std::vector<LampPath> lit;  // the lamps that light the point
  int facing_away = 0;        // lamps behind the surface
  int shadowed = 0;           // lamps hidden by the scene
};

// The light path of every lamp that lights p_W (normal n_W, either side: it
// is turned to face `viewer_W`, the UHI's centre). `shadows` may be null (no
// shadow test).
LampPathsAtPoint lampPathsAt(const LampsInWorld& lamps, const Eigen::Vector3d& p_W, Eigen::Vector3d n_W,
                             const Eigen::Vector3d& viewer_W, const MeshRayCaster* shadows,
                             double shadow_skip_m = 0.005);

// The unit face normal of triangle `triangle` of the mesh (winding as stored).
Eigen::Vector3d triangleNormal(const MeshRayCaster& mesh, int triangle);

}  // namespace hsmap
