#include "pipelines/radiometry/lamp_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hsmap {
namespace {

LightsConfig twoLamps() {
  LightsConfig lights;
  lights.lamps = {{Eigen::Vector3d(-0.3, -0.3, 0.0), Eigen::Vector3d::UnitZ()},
                  {Eigen::Vector3d(0.3, -0.3, 0.0), Eigen::Vector3d::UnitZ()}};
  return lights;
}

TEST(LampGeometry, PlacesTheLampsThroughTheUhiPoseAndTheExtrinsic) {
  // U 0.1 m along C's x; the line's pose a quarter turn about W's z and 5 m down.
  const SE3d T_C_U(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, 0.0, 0.0));
  const SE3d T_W_U(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())),
                   Eigen::Vector3d(0.0, 0.0, 5.0));
  const LampsInWorld lamps = lampsInWorld(twoLamps(), T_W_U, T_C_U);
  ASSERT_EQ(lamps.p_W.size(), 2u);
  // T_W_C = T_W_U T_C_U^-1: the camera centre is U's minus 0.1 m along C's x (W's y).
  const SE3d T_W_C = T_W_U * T_C_U.inverse();
  EXPECT_TRUE(lamps.p_W[0].isApprox(T_W_C * Eigen::Vector3d(-0.3, -0.3, 0.0), 1e-12));
  EXPECT_NEAR((T_W_C.t - Eigen::Vector3d(0.0, -0.1, 5.0)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(lamps.axis_W[1].isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(LampGeometry, RangeIncidenceAndOffAxisAngleOfEachLamp) {
  const LampsInWorld lamps = lampsInWorld(twoLamps(), SE3d(), SE3d());
  // A point 2 m below the camera on a floor facing up (normal given downwards:
  // it is turned to face the viewer).
  const Eigen::Vector3d p(0.0, 0.0, 2.0);
  const LampPathsAtPoint paths = lampPathsAt(lamps, p, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero(), nullptr);
  ASSERT_EQ(paths.lit.size(), 2u);
  const double r = std::sqrt(0.09 + 0.09 + 4.0);
  for (const LampPath& path : paths.lit) {
    EXPECT_NEAR(path.range_m, r, 1e-12);
    EXPECT_NEAR(path.cos_incidence, 2.0 / r, 1e-12);
    EXPECT_NEAR(path.off_axis_rad, std::acos(2.0 / r), 1e-12);
  }
  // Behind the surface: a wall facing away from the lamps.
  const LampPathsAtPoint behind =
      lampPathsAt(lamps, Eigen::Vector3d(0.0, 1.0, 0.0), Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.0, 2.0, 0.0),
                  nullptr);
  EXPECT_EQ(behind.lit.size(), 0u);
  EXPECT_EQ(behind.facing_away, 2);
}

TEST(LampGeometry, AShadowRayThroughTheMeshHidesALamp) {
  const LampsInWorld lamps = lampsInWorld(twoLamps(), SE3d(), SE3d());
  // The floor at z = 2 and a plate halfway between the port lamp and the point below the camera.
  const std::vector<Eigen::Vector3d> vertices = {{-5, -5, 2}, {5, -5, 2}, {5, 5, 2}, {-5, 5, 2},
                                                 {-0.25, -0.25, 1.0}, {-0.05, -0.25, 1.0}, {-0.05, -0.05, 1.0},
                                                 {-0.25, -0.05, 1.0}};
  const std::vector<Eigen::Vector3i> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const MeshRayCaster mesh(vertices, triangles);
  const LampPathsAtPoint paths =
      lampPathsAt(lamps, Eigen::Vector3d(0.0, 0.0, 2.0), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d::Zero(), &mesh);
  EXPECT_EQ(paths.shadowed, 1);
  ASSERT_EQ(paths.lit.size(), 1u);
  // The starboard lamp still lights it, and the floor it starts on does not shadow it.
  EXPECT_NEAR(paths.lit[0].range_m, std::sqrt(0.18 + 4.0), 1e-12);
  EXPECT_TRUE(triangleNormal(mesh, 0).cwiseAbs().isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
}

}  // namespace
}  // namespace hsmap
